"""Security envelope of V2X packets: IEEE 1609.2 signed data as profiled by ETSI TS 103 097 v1.3.1."""
