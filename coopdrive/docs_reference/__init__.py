"""The documentation's reference pages, generated from the code at build time (docs/hooks/reference.py): the command
line from its argparse parser, config keys from the services' pydantic models, topics and messages from the
services table and the protobuf descriptors. A new flag, key or topic appears in the docs without a page edit."""
