"""The reference pages are generated from the code: a new flag, subcommand, config key or topic is in the docs
without a page edit."""

import argparse
import math
from typing import Annotated, Literal, Union

from pydantic import BaseModel, Field

from coopdrive.bus.services import SERVICES
from coopdrive.bus.topics import topic_registry
from coopdrive.cli import build_parser
from coopdrive.docs_reference.cli_reference import cli_markdown
from coopdrive.docs_reference.config_reference import models_markdown, services_config_markdown
from coopdrive.docs_reference.model_reference import model_sections
from coopdrive.docs_reference.topics_reference import topics_markdown


def test_a_new_flag_and_a_new_subcommand_appear_in_the_cli_reference_without_a_page_edit():
    parser = build_parser()
    run = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices["run"]
    run.add_argument("--brake-test-gap", type=float, default=7.5, metavar="METRES", help="a flag added today")
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    bench = commands.add_parser("bench", help="benchmarks")
    compare = bench.add_subparsers(dest="what").add_parser("compare", help="two benchmark runs side by side")
    compare.add_argument("--format", choices=["table", "json"], default="table", help="how to print")
    page = cli_markdown(parser)
    assert "| `--brake-test-gap METRES` | a flag added today | `7.5` |" in page
    assert "## `coopdrive bench compare`" in page
    assert "| `--format FORMAT` | how to print | `table` | `table`, `json` |" in page
    assert "[`compare`](#coopdrive-bench-compare)" in page


def test_every_command_of_the_parser_has_a_section_and_hidden_options_stay_hidden():
    page = cli_markdown(build_parser())
    for command in ("coopdrive run", "coopdrive replay", "coopdrive v2x decode", "coopdrive pki init"):
        assert f"## `{command}`" in page
    assert "--pki" not in page  # v2x decode's older name of --trust, argparse.SUPPRESS


class Gap(BaseModel):
    # The gap kept at a standstill.
    standstill_m: float = 6.0


class Outage(BaseModel):
    """The receiver reports no fix."""
    type: Literal["outage"]
    start_s: float = Field(ge=0)


class Jump(BaseModel):
    type: Literal["jump"]
    east_m: float = 5.0


class Example(BaseModel):
    # How often the service runs.
    rate_hz: float = 25.0
    gap: Gap = Gap()
    horizon_s: float = math.inf  # open-ended
    faults: list[Annotated[Union[Outage, Jump], Field(discriminator="type")]] = []
    mode: Literal["fast", "exact"] = "exact"
    name: str = Field(description="the vehicle's name")


def test_a_new_pydantic_field_appears_with_its_comment_type_and_default():
    class Extended(Example):
        # A key added today.
        lead_s: float = 0.1

    page = models_markdown("# Config", [("`example`", Extended)])
    assert "| `rate_hz` | float | `25.0` | How often the service runs. |" in page
    assert "| `lead_s` | float | `0.1` | A key added today. |" in page
    assert "| `gap.standstill_m` | float | `6.0` | The gap kept at a standstill. |" in page
    assert "| `horizon_s` | float | `inf` | open-ended |" in page
    assert "| `mode` | one of fast, exact | `exact` |" in page
    assert "| `name` | str | required | the vehicle's name |" in page


def test_each_variant_of_a_tagged_union_is_a_section_with_its_own_keys():
    sections = model_sections(Example, "example")
    assert [s.title for s in sections] == ["example", "faults[] with type: outage", "faults[] with type: jump"]
    assert sections[1].description == "The receiver reports no fix."
    assert [row.key for row in sections[2].rows] == ["faults[].type", "faults[].east_m"]


def test_every_service_of_the_services_table_has_its_config_keys_in_the_reference():
    page = services_config_markdown()
    for entry in SERVICES:
        assert f"## `{entry.name}`" in page
    assert "| `geolocator.jerk_std_mps3` | float | `0.5` |" in page
    assert "| `cpu_nice` |" in page


def test_every_topic_and_the_fields_of_its_message_are_in_the_topics_reference():
    page = topics_markdown()
    for topic in topic_registry().values():
        assert f"| `{topic.name}` | [`{topic.message_type.DESCRIPTOR.name}`]" in page
        assert f"### `{topic.type_name}`" in page
    assert "| `steering_angle_request_rad` | double | 3 | Road-wheel angle request, positive left. |" in page
