"""examples/sweep_plot.py end to end on a tiny spec: the plot, its text chunks, its CSV."""

import json
import os
import subprocess
import sys

import pandas as pd
from PIL import Image as PILImage

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "examples")


def test_sweep_plot_writes_the_plot_with_its_provenance(tmp_path):
    spec = {"techniques": ["modern.hw", "modern.gems4"], "scenes": ["fence"],
            "sizes": ["64x48"], "shadow_maps": [256, 512], "repeat": 1}
    (tmp_path / "spec.json").write_text(json.dumps(spec))
    done = subprocess.run([sys.executable, os.path.join(EXAMPLES, "sweep_plot.py"), "--spec",
                           str(tmp_path / "spec.json"), "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    plot = tmp_path / "out" / "sweep-fence-64x48.png"
    with PILImage.open(plot) as image:
        assert image.size == (800, 500)
        assert json.loads(image.text["shadowlab:parameters"]) == spec
        assert image.text["Software"].startswith("shadowlab ")
        assert "sweep_plot.py" in image.text["shadowlab:command"]
    rows = pd.read_csv(tmp_path / "out" / "sweep.csv")
    assert len(rows) == 4 and set(rows["technique"]) == {"modern.hw", "modern.gems4"}


def test_sweep_plot_refuses_a_bad_spec_in_one_line(tmp_path):
    (tmp_path / "spec.json").write_text(json.dumps({"techniques": ["nope"]}))
    done = subprocess.run([sys.executable, os.path.join(EXAMPLES, "sweep_plot.py"), "--spec",
                           str(tmp_path / "spec.json"), "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr.startswith("sweep_plot: unknown technique 'nope'")
    assert done.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()
