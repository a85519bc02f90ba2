"""coopdrive services: one package per service."""
