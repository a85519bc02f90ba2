"""The actuation service."""
