"""The error of a bus session that needs credentials and could not open (no imports: the command line catches it
without loading the bus)."""


class BusCredentialsError(RuntimeError):
    """A session over mutual TLS could not open, and its own files say why (one line)."""
