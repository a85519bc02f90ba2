"""Conversion between asn1tools value dicts and the coopdrive.v1 its protobuf messages.

These modules are the one place where the field list of each message is written.
"""
