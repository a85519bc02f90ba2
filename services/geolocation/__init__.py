"""The geolocation service."""
