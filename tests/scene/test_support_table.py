"""The support table's two ways to the same numbers: array operations over many rows and slots, and one entry at a
time in plain floats (a single V2V message, a single property's read)."""

import numpy as np
import pytest

from coopdrive.services.scene.config import SceneFusionConfig
from coopdrive.services.scene.support_table import SOURCE_COLUMNS, SupportTable

CONFIG = SceneFusionConfig()
SOURCES = (1, 2, 3, 4, 5)
SLOTS = 3


def table() -> SupportTable:
    return SupportTable(CONFIG.source, SLOTS, new_data_bias=3.0, closer_bias=[1.0, 1.5, 2.0])


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_readings_one_by_one_and_as_arrays_give_the_same_table(seed):
    rng = np.random.default_rng(seed)
    by_arrays, one_by_one = table(), table()
    rows = [by_arrays.allocate() for _ in range(6)]
    assert rows == [one_by_one.allocate() for _ in range(6)]
    time_s = 0.0
    for _ in range(120):
        # Mostly forward in time, sometimes a late reading; qualities include none at all and out of range.
        time_s += rng.choice([0.0, 0.05, 0.3, 1.5])
        reading_s = time_s - rng.choice([0.0, 0.0, 0.2])
        row, slot, source = int(rng.choice(rows)), int(rng.integers(SLOTS)), int(rng.choice(SOURCES))
        quality = float(rng.choice([0.0, 0.3, 1.0, 1.2]))
        if rng.random() < 0.5:
            by_arrays.support([row], [slot], source, reading_s, quality)
            one_by_one.support_one(row, slot, source, reading_s, quality)
        else:
            value = float(rng.uniform(1.0, 5.0))
            by_arrays.update([row], [slot], source, reading_s, value, quality)
            one_by_one.update_one(row, slot, source, reading_s, value, quality)
        fused, source_codes = by_arrays.confidences(rows, time_s)
        for k, r in enumerate(rows):
            for s in range(SLOTS):
                confidence, sources = one_by_one.confidence_one(r, s, time_s)
                assert confidence == pytest.approx(fused[k, s], abs=1e-12)
                assert sources == [b for b in range(SOURCE_COLUMNS) if source_codes[k, s] >> b & 1]
        # faded(): one by one for a few rows, as arrays for more.
        for s in range(SLOTS):
            assert by_arrays.faded(rows, s, time_s) == (fused[:, s] == -1.0).tolist()
            assert by_arrays.faded(rows[:2], s, time_s) == (fused[:2, s] == -1.0).tolist()
    np.testing.assert_allclose(one_by_one.values(rows), by_arrays.values(rows), rtol=0.0, atol=1e-12)
