"""The error of a bus session that needs credentials and could not open (no imports: the command line catches it
without loading the bus)."""

# How to mend it, ending each such error's line.
REMEDY = "make the vehicle's bus credentials with `coopdrive pki bus DIR --vehicle ID`"
# Set to "mtls" (the vehicle's compose profile sets it), a session that would not be authenticated does not open.
REQUIRED_MODE_VARIABLE = "COOPDRIVE_BUS_SECURITY"


class BusCredentialsError(RuntimeError):
    """A session over mutual TLS could not open, and its own files say why (one line)."""
