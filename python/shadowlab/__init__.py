"""shadowlab from Python: render, compare, bench and sweep, as the command line does.

Every function runs the command line's own code (the compiled half, _shadowlab): the keyword
arguments are spelled as the CLI's options and parsed by its parser, so a row from Python
equals the CLI's for the same options, and bad input raises ValueError with the CLI's one-line
message. Manual: docs/python.md.

    import shadowlab
    r = shadowlab.render(scene="brabec", technique="modern.pcf", size=(320, 240))
    r["image"].shape, r["mask"].mean(), r["frame_ms"]
"""

import io
import json
import numbers
import os
import warnings

# An installed package (`pip install .`, setup.py) carries the assets the library reads at run
# time (scenes, meshes, lessons, the course) beside this file; the build tree's package
# (PYTHONPATH=build/python) has none and uses the source tree's. SHADOWLAB_ASSETS, when set, wins.
_ASSETS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "assets")
if os.path.isdir(_ASSETS) and not os.environ.get("SHADOWLAB_ASSETS"):
    os.environ["SHADOWLAB_ASSETS"] = _ASSETS

from . import _shadowlab as _core
from ._shadowlab import GLError

__all__ = ["techniques", "scenes", "render", "compare", "bench", "sweep", "sweep_rows", "merge",
           "commit", "GLError"]

# The columns of bench and sweep rows that hold text; every other column is numeric (an empty
# cell: not measured, NaN).
_TEXT_COLUMNS = {"scene", "technique", "variant", "status", "reference", "precision", "params",
                 "metric", "passes", "orbit", "backend", "gl_vendor", "gl_renderer", "gl_version",
                 "date", "commit", "command"}

# The columns of whole numbers (a size, a count, a rank).
_COUNT_COLUMNS = {"width", "height", "shadow_map", "filter", "pareto_rank", "scored_pixels",
                  "frames_timed", "spread_large"}

# A sweep's rows of one view are measured in tasks of at most this many rows: the references of
# a view are rendered once per process that measures any of its rows.
_SWEEP_TASK_ROWS = 16

# This process's references of the views it has measured (each Dask worker process has its own).
_REFERENCES = _core.ReferenceCache()


def commit():
    """The commit this module was built from (the rows' and JSON lines' "commit")."""
    return _core.commit()


def techniques():
    """Every technique: name, paper, summary, status, the common options it reads and its
    --param declarations (key, kind, default, choices, meaning), as `shadowlab list` shows."""
    return _core.techniques()


def scenes():
    """Every scene name: the built-in ones and assets/scenes/*.json."""
    return _core.scenes()


def _text(value):
    """A value as the command line spells it."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "on" if value else "off"  # the flags' words (shadowlab list: on|off)
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    raise TypeError(f"expected a string or a number, got {value!r}")


def _joined(value, separator):
    """(w, h) -> "WxH"; (x, y, z) -> "X,Y,Z"; a string as it is."""
    if isinstance(value, str):
        return value
    if not isinstance(value, (tuple, list)) or not all(
            isinstance(v, numbers.Real) and not isinstance(v, bool) for v in value):
        raise TypeError(f"expected a string or a tuple of numbers, got {value!r}")
    return separator.join(_text(v) for v in value)


# Keyword -> (command-line option, how its value is spelled).
_OPTIONS = {
    "scene": ("scene", _text),
    "technique": ("technique", _text),
    "a": ("a", _text),
    "b": ("b", _text),
    "size": ("size", lambda v: _joined(v, "x")),
    "shadow_map": ("shadow-map", _text),
    "filter": ("filter", _text),
    "precision": ("precision", _text),
    "backend": ("backend", _text),
    "imaging": ("imaging", _text),
    "orbit": ("orbit", lambda v: _joined(v, ",")),
    "camera_distance": ("camera-distance", _text),
    "light_radius": ("light-radius", _text),
    "light_position": ("light-position", lambda v: _joined(v, ",")),
    "threshold": ("threshold", _text),
    "repeat": ("repeat", _text),
}
# Keyword -> option repeated once per key=value of a dict.
_PARAM_OPTIONS = {"params": "param", "a_params": "a-param", "b_params": "b-param"}


def _arguments(options):
    """The command line of `options` (None: not given), each as --option=value."""
    out = []
    for name, value in options.items():
        if value is None:
            continue
        if name in _PARAM_OPTIONS:
            if not isinstance(value, dict):
                raise TypeError(f"{name} must be a dict of key: value, got {value!r}")
            out += [f"--{_PARAM_OPTIONS[name]}={k}={_text(v)}" for k, v in value.items()]
        elif name in ("scenes", "techniques"):
            names = [value] if isinstance(value, str) else list(value)
            out += [f"--{name[:-1]}={_text(n)}" for n in names]
        elif name == "quick":
            out += ["--quick"] if value else []
        else:
            option, spell = _OPTIONS[name]
            out.append(f"--{option}={spell(value)}")
    return out


def _call(function, options):
    """What made an output: this call, as Python spells it (the rows' "command")."""
    given = ", ".join(f"{k}={v!r}" for k, v in options.items() if v is not None)
    return f"shadowlab.{function}({given})"


def render(scene=None, technique=None, size=None, shadow_map=None, filter=None, precision=None,
           params=None, backend=None, imaging=None, orbit=None, camera_distance=None,
           light_radius=None, light_position=None, passes=False):
    """Renders one technique, as `shadowlab render` does.

    Options as the CLI's (None: its default): scene (name or .json file), technique, size
    (w, h) or "WxH", shadow_map, filter, precision (8, 12 or "float"), params (dict: --param
    key=value), backend ("osmesa", "egl", "reference"), imaging, orbit (az, el, dist),
    camera_distance, light_radius, light_position (x, y, z).

    Returns a dict: the fields of render's JSON line (technique, scene, size, shadow_map, filter,
    precision, backend, imaging, params, command, commit, frame_ms, passes, counters, ...),
    "image" (uint8, (h, w, 3): the bytes --out's PNG holds), "mask" (float32, (h, w): the light
    visibility, 1 = lit, 0 = umbra; --mask's PNG holds it rounded to 16 bits) and, with
    passes=True, "pass_buffers" (name -> float32 (h, w, c), pipeline order) and "pass_captions".
    Bad input: ValueError with the CLI's message. GL failure: GLError.
    """
    options = dict(scene=scene, technique=technique, size=size, shadow_map=shadow_map,
                   filter=filter, precision=precision, params=params, backend=backend,
                   imaging=imaging, orbit=orbit, camera_distance=camera_distance,
                   light_radius=light_radius, light_position=light_position)
    line, image, mask, buffers = _core.render(_arguments(options),
                                              _call("render", options), bool(passes))
    out = json.loads(line)
    out["image"] = image
    out["mask"] = mask
    if passes:
        out["pass_buffers"] = {name: array for name, _, array in buffers}
        out["pass_captions"] = {name: caption for name, caption, _ in buffers}
    return out


def compare(scene=None, a=None, b=None, size=None, shadow_map=None, filter=None, precision=None,
            params=None, a_params=None, b_params=None, threshold=None, backend=None,
            imaging=None, orbit=None, camera_distance=None, light_radius=None,
            light_position=None):
    """Renders techniques a and b and scores them, as `shadowlab compare` does.

    Options as render's, plus a_params / b_params (one side's --params) and threshold. Returns
    the fields of compare's JSON line (metric, truth, rmse, band_rmse, leak_share, left_out,
    all_pixels, a_params, b_params, command, commit, a_frame_ms, b_frame_ms, ...). An option
    one side ignores is a UserWarning (the CLI's warning line).
    """
    options = dict(scene=scene, a=a, b=b, size=size, shadow_map=shadow_map, filter=filter,
                   precision=precision, params=params, a_params=a_params, b_params=b_params,
                   threshold=threshold, backend=backend, imaging=imaging, orbit=orbit,
                   camera_distance=camera_distance, light_radius=light_radius,
                   light_position=light_position)
    line, notes = _core.compare(_arguments(options), _call("compare", options))
    for note in notes:
        warnings.warn(note, UserWarning, stacklevel=2)
    return json.loads(line)


def _frame(csv_text):
    """A DataFrame of the bench's CSV text: the text columns as str (empty: ""), the counts as
    Int64 (empty: <NA>), every other column as float64 (empty: NaN); a column the bench adds
    later is numeric when every non-empty cell is a number, else text."""
    import pandas as pd
    frame = pd.read_csv(io.StringIO(csv_text), dtype=str, keep_default_na=False)
    for column in frame.columns:
        if column in _TEXT_COLUMNS:
            continue
        try:  # float() reads back every double exactly (pandas.to_numeric may not)
            values = frame[column].map(lambda cell: float(cell) if cell else float("nan"))
        except ValueError:
            continue  # words: keep the column as text
        frame[column] = values.astype("Int64") if column in _COUNT_COLUMNS else \
            values.astype("float64")
    return frame


def bench(scenes=None, techniques=None, quick=False, size=None, backend=None, repeat=None,
          progress=False):
    """The rows of `shadowlab bench` (same options: scenes and techniques are names or lists
    of names, quick, size, backend, repeat) as a pandas DataFrame with its CSV's columns, in
    its order (by scene, then frame time), full double precision. progress=True prints the
    CLI's progress lines on stderr. Writes no file (the CLI's plots and claims are not made).
    """
    options = dict(scenes=scenes, techniques=techniques, quick=quick or None, size=size,
                   backend=backend, repeat=repeat)
    return _frame(_core.bench(_arguments(options), _call("bench", options), bool(progress)))


def sweep_rows(spec):
    """The rows `sweep(spec)` would measure (row, view, scene, width, height, orbit, technique,
    variant), checked but not measured: ValueError for a spec sweep() would refuse."""
    import pandas as pd
    return pd.DataFrame(json.loads(_core.sweep_plan(json.dumps(spec))),
                        columns=["row", "view", "scene", "width", "height", "orbit", "technique",
                                 "variant"])


def _measure_rows(spec_json, indices, command):
    """Measures some of a sweep's rows in this process (a Dask task runs this on a worker;
    its references stay cached in the worker process for its next tasks)."""
    return _core.sweep_measure(spec_json, list(indices), command, _REFERENCES)


def sweep(spec, client=None, task_rows=_SWEEP_TASK_ROWS):
    """Measures every row of a sweep spec (a dict; its keys: docs/python.md "Sweeps") and
    returns a DataFrame: the bench's columns, plus "orbit", one row per spec row in the spec's
    order, Pareto ranks within each view (scene, size, orbit).

    client=None: in this process. client=dask.distributed.Client(...): the rows run as Dask
    tasks on its workers (each worker process imports this module and makes its own GL; nothing
    is shared), and the DataFrame is the same as the local run's (the times, their spread, the
    load and the date differ, as any two runs' do). task_rows: at most this many rows of one view per task (each process renders a
    view's references once, for its first task of that view).
    """
    import pandas as pd
    if not isinstance(task_rows, numbers.Integral) or task_rows < 1:
        raise ValueError(f"task_rows must be a whole number >= 1, got {task_rows!r}")
    spec_json = json.dumps(spec)
    plan = json.loads(_core.sweep_plan(spec_json))  # ValueError before anything runs
    command = f"shadowlab.sweep({spec_json})"
    tasks = []  # consecutive rows of one view, at most _SWEEP_TASK_ROWS each
    for row in plan:
        if tasks and tasks[-1][0] == row["view"] and len(tasks[-1][1]) < task_rows:
            tasks[-1][1].append(row["row"])
        else:
            tasks.append((row["view"], [row["row"]]))
    if client is None:
        texts = [_measure_rows(spec_json, rows, command) for _, rows in tasks]
    else:
        futures = [client.submit(_measure_rows, spec_json, rows, command, pure=False)
                   for _, rows in tasks]
        texts = client.gather(futures)
    header, _, _ = texts[0].partition("\n")
    body = "".join(text.partition("\n")[2] for text in texts)
    frame = _frame(header + "\n" + body)
    frame["orbit"] = [row["orbit"] or "" for row in plan]
    groups = [f'{row["scene"]}|{row["width"]}x{row["height"]}|{row["orbit"] or ""}'
              for row in plan]
    return _ranked(frame, groups)


def _ranked(frame, groups):
    """`frame` with pareto_rank recomputed within each group (the C++ ranking of the bench)."""
    import pandas as pd
    ranks = _core.pareto_ranks(groups, list(frame["technique"]), list(frame["status"]),
                               list(frame["reference"]),
                               [float(v) for v in frame["frame_ms"].fillna(0.0)],
                               [float(v) for v in frame["hard_rmse"].fillna(0.0)],
                               [float(v) for v in frame["soft_rmse"].fillna(0.0)])
    frame["pareto_rank"] = pd.array([r if r > 0 else None for r in ranks], dtype="Int64")
    return frame


def merge(*frames):
    """The rows of several bench() / sweep() DataFrames as one, with pareto_rank recomputed over
    all of them within each scene, window and orbit (the ranking `shadowlab bench --merge`
    applies to JSON lines, the same C++). Every other column is kept as it was measured."""
    import pandas as pd
    if not frames:
        raise ValueError("merge: no DataFrames given")
    frame = pd.concat(frames, ignore_index=True)
    orbits = frame["orbit"].fillna("") if "orbit" in frame else [""] * len(frame)
    groups = [f"{scene}|{width}x{height}|{orbit}" for scene, width, height, orbit in
              zip(frame["scene"], frame["width"], frame["height"], orbits)]
    return _ranked(frame, groups)
