"""zscan.query: per object the pixels (or samples) it owns and its box's
query samples, the figures `zscan query --format json` prints."""
import json
import subprocess

import pytest

import zscan
from conftest import CLI, CLI_ENV


def command(*args):
    out = subprocess.run([CLI, "query", *args, "--format", "json"], capture_output=True,
                         text=True, env=CLI_ENV, check=True).stdout
    return [{"name": o["name"], "visible": o["visible"], "bbox": o["bbox"]}
            for o in json.loads(out)["objects"]]


@pytest.mark.parametrize("samples", [1, 4])
def test_query_equals_the_command(samples):
    mine = zscan.query("builtin:cubes?n=2", size=(160, 120), samples=samples)
    assert mine == command("builtin:cubes?n=2", "--size", "160x120", "--samples", str(samples))
    assert len(mine) == 8 and sum(o["visible"] for o in mine) > 0


def test_samples_count_samples():
    one = zscan.query("builtin:cubes?n=2", size=(64, 48))
    four = zscan.query("builtin:cubes?n=2", size=(64, 48), samples=4)
    assert sum(o["visible"] for o in four) <= 4 * 64 * 48
    assert [o["name"] for o in one] == [o["name"] for o in four]
    # edges own a share of their pixels' samples: not four times the pixels
    assert sum(o["visible"] for o in four) != 4 * sum(o["visible"] for o in one)


def test_bad_samples_are_refused():
    with pytest.raises(ValueError, match=r"^samples: expected 1, 2, 4, 8 or 16, got 3$"):
        zscan.query("builtin:cubes?n=2", size=(16, 12), samples=3)
    with pytest.raises(TypeError, match=r"^samples: expected an integer, got 2.0$"):
        zscan.query("builtin:cubes?n=2", size=(16, 12), samples=2.0)
