"""Scenario definitions shipped with coopdrive (YAML)."""
