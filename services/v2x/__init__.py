"""The v2x service."""
