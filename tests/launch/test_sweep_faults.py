"""A sweep's faults file: variant names to fault lists, each fault as a scenario writes it; a bad file is one line
naming what is wrong."""

from pathlib import Path

import pytest

from coopdrive.launch.sweep_faults import FaultsFileError, load_fault_variants

SAMPLE = Path(__file__).parents[2] / "docs" / "sweep-faults.yaml"


def write(tmp_path, text: str) -> Path:
    path = tmp_path / "faults.yaml"
    path.write_text(text)
    return path


def test_each_variant_keeps_its_name_and_its_faults_in_the_files_order(tmp_path):
    variants = load_fault_variants(write(tmp_path, """
none: []
lossy:
  - {type: v2v_loss, start_s: 0, loss_probability: 0.3}
  - {type: v2v_corruption, start_s: 10}
"""))
    assert list(variants) == ["none", "lossy"]
    assert variants["none"] == ()
    assert [fault["type"] for fault in variants["lossy"]] == ["v2v_loss", "v2v_corruption"]


def test_the_documented_sample_loads_and_starts_with_the_scenarios_as_they_are():
    variants = load_fault_variants(SAMPLE)
    assert variants["none"] == () and len(variants) >= 3


@pytest.mark.parametrize("text, message", [
    ("[1", "not YAML at line"),
    ("- {type: v2v_loss, start_s: 0}", "a mapping of variant names to lists of faults"),
    ("", "a mapping of variant names to lists of faults"),
    ("a/b: []", "variant name 'a/b': letters, digits"),
    ("lossy: {type: v2v_loss, start_s: 0}", "variant 'lossy': a list of faults (give [] for none)"),
    ("lossy: [v2v_loss]", "variant 'lossy', fault 0: a mapping such as"),
    ("lossy: [{type: v2v_loss, start_s: 0, loss_probability: 2}]",
     "variant 'lossy', fault 0: loss_probability: Input should be less than or equal to 1"),
    ("cut: [{type: v2v_loss, start_s: 0}, {type: teleport, start_s: 1}]", "variant 'cut', fault 1: Input tag 'teleport'"),
    ("late: [{type: v2v_loss, start_s: 5, end_s: 2}]", "variant 'late', fault 0: end_s 2.0 must be after start_s 5.0"),
])
def test_a_bad_faults_file_is_refused_in_one_line_naming_the_file_and_what_is_wrong(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(FaultsFileError) as raised:
        load_fault_variants(path)
    assert str(raised.value).startswith(f"{path}: ") and message in str(raised.value)
    assert "\n" not in str(raised.value)


def test_a_missing_faults_file_is_named(tmp_path):
    with pytest.raises(FaultsFileError, match="missing.yaml: cannot read: No such file"):
        load_fault_variants(tmp_path / "missing.yaml")
