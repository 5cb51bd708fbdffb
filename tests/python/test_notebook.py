"""examples/error_vs_time.ipynb executed end to end by nbclient (Debian's python3-nbclient and
python3-ipykernel): every cell runs without an error, the table and the Pareto front are
DataFrames of the sweep's rows, and the plot is an image."""

import os

import nbclient
import nbformat

NOTEBOOK = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "error_vs_time.ipynb")
# The sweep is 13 rows at 160x120; the whole notebook runs in about 20 s here.
CELL_TIMEOUT_S = 600


def outputs_of(cell):
    return [o for o in cell.get("outputs", [])]


def test_the_notebook_runs_and_shows_its_table_front_and_plot(tmp_path):
    nb = nbformat.read(NOTEBOOK, as_version=4)
    # The kernel inherits this process's environment: PYTHONPATH=build/python (ctest).
    nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT_S, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    code = [c for c in nb.cells if c.cell_type == "code"]
    errors = [o for c in code for o in outputs_of(c) if o.output_type == "error"]
    assert not errors, errors
    html = [o["data"]["text/html"] for c in code for o in outputs_of(c)
            if o.output_type == "execute_result" and "text/html" in o.get("data", {})]
    assert len(html) == 2  # the table and the front
    assert "hard_point_rmse" in html[0] and "modern.volumes" in html[0]
    assert "modern.volumes" in html[1]  # exact and fast here: always on the front
    images = [o for c in code for o in outputs_of(c) if "image/png" in o.get("data", {})]
    assert len(images) == 1
