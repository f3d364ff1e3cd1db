"""The tile client's HTTPS through :mod:`hamta.core.basemap.http`: the certificate and the host it names are
checked, and a connection is watched (shut on a cancel) from before its TLS handshake."""
import datetime
import socket
import ssl
import threading
import time

import pytest

from hamta.core.basemap import http

BODY = b"a tile"


def _certificates(folder):
    """(CA certificate file, server certificate-and-key file): a CA of its own signs a certificate for 'localhost'."""
    x509 = pytest.importorskip("cryptography.x509")
    from cryptography.hazmat.primitives import hashes, serialization
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import NameOID

    now = datetime.datetime.now(datetime.timezone.utc)

    def certificate(name, key, issuer, issuer_key, ca, extra=()):
        builder = (x509.CertificateBuilder().subject_name(name).issuer_name(issuer).public_key(key.public_key())
                   .serial_number(x509.random_serial_number()).not_valid_before(now - datetime.timedelta(days=1))
                   .not_valid_after(now + datetime.timedelta(days=1))
                   .add_extension(x509.BasicConstraints(ca=ca, path_length=None), critical=True)
                   .add_extension(x509.SubjectKeyIdentifier.from_public_key(key.public_key()), critical=False)
                   .add_extension(x509.AuthorityKeyIdentifier.from_issuer_public_key(issuer_key.public_key()),
                                  critical=False))
        for extension in extra:
            builder = builder.add_extension(extension, critical=False)
        return builder.sign(issuer_key, hashes.SHA256())

    ca_key, key = ec.generate_private_key(ec.SECP256R1()), ec.generate_private_key(ec.SECP256R1())
    ca_name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "Hamta test CA")])
    ca_usage = x509.KeyUsage(digital_signature=True, content_commitment=False, key_encipherment=False,
                             data_encipherment=False, key_agreement=False, key_cert_sign=True, crl_sign=True,
                             encipher_only=False, decipher_only=False)
    ca = certificate(ca_name, ca_key, ca_name, ca_key, True, [ca_usage])
    leaf = certificate(x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "localhost")]), key, ca_name, ca_key,
                       False, [x509.SubjectAlternativeName([x509.DNSName("localhost")])])
    ca_file, leaf_file = folder / "ca.pem", folder / "localhost.pem"
    ca_file.write_bytes(ca.public_bytes(serialization.Encoding.PEM))
    leaf_file.write_bytes(leaf.public_bytes(serialization.Encoding.PEM) + key.private_bytes(
        serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8, serialization.NoEncryption()))
    return ca_file, leaf_file


class Listener:
    """A local server on 127.0.0.1 that answers each connection with ``handle(socket)``, in a thread."""

    def __init__(self, handle):
        self.socket = socket.create_server(("127.0.0.1", 0))
        self.socket.settimeout(0.1)
        self.port = self.socket.getsockname()[1]
        self.stopped = threading.Event()
        self.thread = threading.Thread(target=self._serve, args=(handle,), daemon=True)
        self.thread.start()

    def _serve(self, handle):
        while not self.stopped.is_set():
            try:
                conn, _ = self.socket.accept()
            except socket.timeout:
                continue
            with conn:
                handle(conn)

    def stop(self):
        self.stopped.set()
        self.thread.join()
        self.socket.close()


@pytest.fixture(scope="module")
def tls(tmp_path_factory):
    """(CA file, port) of a server that answers ``BODY`` over TLS with a certificate for 'localhost'."""
    ca_file, leaf_file = _certificates(tmp_path_factory.mktemp("tls"))
    context = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
    context.load_cert_chain(leaf_file)

    def answer(conn):
        try:
            with context.wrap_socket(conn, server_side=True) as secure:
                secure.recv(1 << 16)
                secure.sendall(b"HTTP/1.1 200 OK\r\nContent-Length: %d\r\nConnection: close\r\n\r\n%s"
                               % (len(BODY), BODY))
        except (ssl.SSLError, OSError):
            pass

    listener = Listener(answer)
    yield ca_file, listener.port
    listener.stop()


def test_https_to_the_host_a_trusted_certificate_names_gets_the_answer(tls, monkeypatch):
    ca_file, port = tls
    monkeypatch.setenv("SSL_CERT_FILE", str(ca_file))
    answer = http.get(f"https://localhost:{port}/0/0/0.png", http.Watch(), timeout_s=10, max_bytes=1 << 20)
    assert (answer.status, answer.body, answer.complete) == (200, BODY, True)


@pytest.mark.parametrize("host, trusted", [("127.0.0.1", True), ("localhost", False)])
def test_https_is_refused_where_the_certificate_names_another_host_or_is_not_trusted(tls, host, trusted,
                                                                                      monkeypatch):
    ca_file, port = tls
    if trusted:
        monkeypatch.setenv("SSL_CERT_FILE", str(ca_file))
    with pytest.raises(http.Failure, match="has a certificate that cannot be trusted") as caught:
        http.get(f"https://{host}:{port}/0/0/0.png", http.Watch(), timeout_s=10, max_bytes=1 << 20)
    assert not caught.value.retry


def test_a_cancel_ends_a_tls_handshake_the_server_never_answers():
    silent = Listener(lambda conn: silent.stopped.wait(30))
    watch = http.Watch()
    threading.Timer(0.3, watch.cancel).start()
    start = time.monotonic()
    try:
        with pytest.raises(http.Canceled):
            http.get(f"https://localhost:{silent.port}/", watch, timeout_s=30, max_bytes=1 << 20)
    finally:
        silent.stop()
    assert time.monotonic() - start < 5
