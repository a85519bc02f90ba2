"""coopdrive: a cooperative automated driving stack on Zenoh."""
