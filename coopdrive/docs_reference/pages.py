"""The generated pages of the documentation site: their path under docs/ and the function that writes each.
docs/hooks/reference.py adds them to the site at build time; none is committed."""

from __future__ import annotations

from typing import Callable

from coopdrive.docs_reference.cli_reference import coopdrive_cli_markdown
from coopdrive.docs_reference.config_reference import (scenario_file_markdown, services_config_markdown,
                                                       vehicle_can_adapter_markdown)
from coopdrive.docs_reference.topics_reference import topics_markdown

GENERATED_PAGES: dict[str, Callable[[], str]] = {
    "reference/cli.md": coopdrive_cli_markdown,
    "reference/config.md": services_config_markdown,
    "reference/scenario-file.md": scenario_file_markdown,
    "reference/vehicle-can-adapter.md": vehicle_can_adapter_markdown,
    "reference/topics.md": topics_markdown,
}
