"""Secrets out of map-service addresses, for messages and reports (no network code here: every run
imports this, few runs fetch tiles)."""
from __future__ import annotations

import re
from urllib.parse import parse_qsl, urlencode, urlsplit, urlunsplit

SECRET_KEYS = frozenset((
    "key", "token", "apikey", "api_key", "access_token", "access_key", "password", "passwd", "signature", "sig",
    "x-amz-signature", "x-amz-credential", "x-amz-security-token", "app_code", "client_id", "client_secret",
    "subscription-key"))


def redact(text: str) -> str:
    """``text`` (a URL, or a GDAL string holding one: ``/vsicurl/https://…``, ``WMTS:https://…``) without
    user name, password or key-like query values, for messages and reports; other text unchanged."""
    found = re.search(r"(https?|ftp)://", text)
    if found is None:
        return text
    prefix, url = text[:found.start()], text[found.start():]
    parts = urlsplit(url)
    netloc = (parts.hostname or "") + (f":{parts.port}" if parts.port else "")
    query = [(k, "***" if k.lower() in SECRET_KEYS else v) for k, v in parse_qsl(parts.query, keep_blank_values=True)]
    text = urlunsplit((parts.scheme, netloc, parts.path, urlencode(query, safe="{}/,:*"), ""))
    return prefix + text.replace("%7B", "{").replace("%7D", "}")
