"""Secrets out of map-service addresses, for messages, reports, logs and batch tables (no network code
here: every run imports this, few runs fetch tiles)."""
from __future__ import annotations

import re
from urllib.parse import parse_qsl, urlencode, urlsplit, urlunsplit

# A query key naming a secret, in any case and with any separator: key, apikey, api-key, X-Api-Key,
# access_token, client_secret, client_id, app_code, sig, X-Amz-Signature, X-Amz-Credential, password, pwd, authcfg…
SECRET_KEY = re.compile(r"key|token|secret|sig|pass|pwd|credential|auth|session|app.?code|app.?id|client.?id",
                        re.IGNORECASE)
URL = re.compile(r"[A-Za-z][A-Za-z0-9+.-]*://[^\s'\"<>]+")
HIDDEN = "***"


def secret_key(name: str) -> bool:
    """Whether a query key (or a QGIS source key) names a secret."""
    return SECRET_KEY.search(name) is not None


def redact(text: str) -> str:
    """``text`` with every address in it (``https://…``, also inside a GDAL string: ``/vsicurl/https://…``,
    ``WMTS:https://…``) stripped of user name, password and secret-like query values; other text unchanged."""
    return URL.sub(lambda found: _redact_url(found.group(0)), str(text))


def _redact_url(url: str) -> str:
    try:
        parts = urlsplit(url)
        port = parts.port
    except ValueError:  # a malformed port or bracket: keep nothing after the scheme that could hold a secret
        return url.split("://", 1)[0] + "://" + HIDDEN
    name = parts.hostname or ""
    netloc = (f"[{name}]" if ":" in name else name) + (f":{port}" if port else "")  # an IPv6 host in brackets
    query = [(k, HIDDEN if secret_key(k) else v) for k, v in parse_qsl(parts.query, keep_blank_values=True)]
    text = urlunsplit((parts.scheme, netloc, parts.path, urlencode(query, safe="{}/,:*"), ""))
    return text.replace("%7B", "{").replace("%7D", "}")


def without_secrets_of(url: str, text: str) -> str:
    """``text`` (a server's answer to ``url``) with the secret values of ``url`` hidden: a server may echo
    the key it was sent ('invalid key: …')."""
    try:
        parts = urlsplit(url)
        values = [v for k, v in parse_qsl(parts.query) if secret_key(k) and len(v) >= 4]
        values += [v for v in (parts.username, parts.password) if v and len(v) >= 4]
    except ValueError:
        return text
    for value in sorted(values, key=len, reverse=True):
        text = text.replace(value, HIDDEN)
    return redact(text)
