"""render(), compare(), techniques(), scenes() and bad input against the CLI."""

import json

import numpy as np
import pytest

import shadowlab
from conftest import json_line, quantized_16, read_png

# Fields of the JSON lines that are measured (times) or say how the output was made: the same
# rows from two runs differ there and only there.
RUN_FIELDS = {"command", "frame_ms", "passes", "a_frame_ms", "b_frame_ms"}


def without_run_fields(fields):
    return {k: v for k, v in fields.items() if k not in RUN_FIELDS}


def test_techniques_and_scenes_match_the_cli_list(cli):
    status, out, _ = cli("list")
    assert status == 0
    names = [t["name"] for t in shadowlab.techniques()]
    assert names, "no technique registered"
    for name in names:
        assert f"  {name} " in out
    pcf = next(t for t in shadowlab.techniques() if t["name"] == "modern.pcf")
    assert pcf["reads"]["filter"] and pcf["reads"]["shadow_map"]
    assert "depth-bias" in [p["key"] for p in pcf["params"]]
    for scene in shadowlab.scenes():
        assert f"  {scene['name']} ({scene['source']})" in out


def test_render_equals_the_cli_render(cli, out_dir):
    options = ["--scene", "fence", "--technique", "modern.pcf", "--size", "64x48",
               "--shadow-map", "256", "--filter", "3", "--param", "depth-bias=3",
               "--orbit", "20,25,9"]
    status, out, err = cli("render", *options, "--out", str(out_dir / "image.png"),
                           "--mask", str(out_dir / "mask.png"))
    assert status == 0, err
    line = json_line(out)
    r = shadowlab.render(scene="fence", technique="modern.pcf", size=(64, 48), shadow_map=256,
                         filter=3, params={"depth-bias": 3}, orbit=(20, 25, 9))
    # Every field the CLI prints, with the same values (times and the command aside).
    assert set(line) <= set(r)
    assert without_run_fields({k: r[k] for k in line}) == without_run_fields(line)
    assert r["command"].startswith("shadowlab.render(scene='fence'")
    assert r["commit"] == shadowlab.commit()
    assert r["frame_ms"] > 0 and set(r["passes"]) == set(line["passes"])
    # The arrays: the image is --out's bytes; the mask rounds to --mask's 16-bit samples.
    assert r["image"].dtype == np.uint8 and r["image"].shape == (48, 64, 3)
    assert r["mask"].dtype == np.float32 and r["mask"].shape == (48, 64)
    assert np.array_equal(r["image"], read_png(out_dir / "image.png"))
    assert np.array_equal(quantized_16(r["mask"]), read_png(out_dir / "mask.png"))
    # The fence casts a shadow here: neither all lit nor all dark (else the equality is empty).
    assert 0.0 < r["mask"].mean() < 1.0 and r["mask"].min() == 0.0


def test_render_pass_buffers_on_request(cli, out_dir):
    plain = shadowlab.render(technique="modern.hw", size=(64, 48))
    assert "pass_buffers" not in plain
    r = shadowlab.render(technique="modern.hw", size=(64, 48), passes=True)
    status, _, err = cli("render", "--technique", "modern.hw", "--size", "64x48",
                         "--out", str(out_dir / "i.png"), "--dump-passes", str(out_dir / "dump"))
    assert status == 0, err
    assert r["pass_buffers"], "modern.hw captured no buffer"
    # --dump-passes writes the same buffers, in the same order, one PNG each (passes.json).
    dumped = json.loads((out_dir / "dump" / "passes.json").read_text())["images"]
    assert [i["caption"] for i in dumped] == list(r["pass_captions"].values())
    for image, (name, buffer) in zip(dumped, r["pass_buffers"].items()):
        assert buffer.dtype == np.float32, name
        assert buffer.shape == (image["height"], image["width"], image["channels"]), name
        assert (out_dir / "dump" / image["file"]).exists(), name
    # Capturing the passes changes nothing in the frame.
    assert np.array_equal(r["mask"], plain["mask"])


def test_compare_equals_the_cli_compare(cli):
    options = ["--scene", "fence", "--a", "modern.hw", "--b", "reference.hard", "--size", "64x48",
               "--b-param", "pixel=area"]
    status, out, err = cli("compare", *options)
    assert status == 0, err
    line = json_line(out)
    r = shadowlab.compare(scene="fence", a="modern.hw", b="reference.hard", size="64x48",
                          b_params={"pixel": "area"})
    assert without_run_fields(r) == without_run_fields(line)
    assert r["truth"] == "reference.hard pixel=area" and r["rmse"] > 0


def test_compare_warns_as_the_cli_does(cli):
    status, _, err = cli("compare", "--a", "modern.pcf", "--b", "modern.hw", "--size", "64x48",
                         "--filter", "3")
    assert status == 0
    with pytest.warns(UserWarning) as caught:
        shadowlab.compare(a="modern.pcf", b="modern.hw", size=(64, 48), filter=3)
    assert [f"shadowlab: warning: {w.message}" for w in caught] == \
        [line for line in err.splitlines() if "warning:" in line]


@pytest.mark.parametrize("python_call, cli_arguments", [
    (dict(technique="nope"), ["--technique", "nope"]),
    (dict(technique="modern.hw", size=(0, 48)), ["--technique", "modern.hw", "--size", "0x48"]),
    (dict(technique="modern.hw", filter=3), ["--technique", "modern.hw", "--filter", "3"]),
    (dict(technique="modern.pcf", params={"foo": 1}),
     ["--technique", "modern.pcf", "--param", "foo=1"]),
    (dict(technique="modern.hw", scene="no-such-scene"),
     ["--technique", "modern.hw", "--scene", "no-such-scene"]),
    (dict(technique="modern.hw", orbit=(0, 95, 5)),
     ["--technique", "modern.hw", "--orbit", "0,95,5"]),
    (dict(technique="modern.csm", params={"order": 99}),
     ["--technique", "modern.csm", "--param", "order=99", "--size", "64x48"]),
    (dict(), []),
])
def test_bad_input_is_value_error_with_the_cli_message(cli, out_dir, python_call, cli_arguments):
    status, _, err = cli("render", *cli_arguments, "--out", str(out_dir / "x.png"))
    assert status == 2, err
    message = err.strip()
    assert message.startswith("shadowlab: ") and "\n" not in message
    if "size" not in python_call and "--size" in cli_arguments:
        python_call = dict(python_call, size=(64, 48))
    with pytest.raises(ValueError) as raised:
        shadowlab.render(**python_call)
    assert str(raised.value) == message[len("shadowlab: "):]
    assert not (out_dir / "x.png").exists()


def test_bad_compare_and_bench_input(cli):
    status, _, err = cli("compare", "--a", "modern.hw", "--b", "modern.pcf", "--threshold", "2")
    assert status == 2
    with pytest.raises(ValueError, match=r"^--threshold must lie in \[0, 1\]$"):
        shadowlab.compare(a="modern.hw", b="modern.pcf", threshold=2)
    assert err.strip() == "shadowlab: --threshold must lie in [0, 1]"
    status, _, err = cli("bench", "--technique", "nope")
    assert status == 2
    with pytest.raises(ValueError) as raised:
        shadowlab.bench(techniques="nope")
    assert "shadowlab: " + str(raised.value) == err.strip()


def test_a_value_of_the_wrong_type_is_a_type_error():
    with pytest.raises(TypeError):
        shadowlab.render(technique="modern.hw", size={"w": 64})
    with pytest.raises(TypeError):
        shadowlab.render(technique="modern.hw", params=["depth-bias=2"])


def test_renders_from_threads_equal_renders_one_after_another():
    # The GIL is released while C++ renders and one lock keeps the GL work one call at a time:
    # four threads get the frames (and the commands) that four calls in a row get.
    from concurrent.futures import ThreadPoolExecutor
    calls = [dict(technique="modern.hw", size=(64, 48)),
             dict(scene="fence", technique="modern.gems4", size=(64, 48))] * 2
    alone = [shadowlab.render(**c) for c in calls]
    with ThreadPoolExecutor(max_workers=4) as pool:
        together = list(pool.map(lambda c: shadowlab.render(**c), calls))
    for a, b in zip(alone, together):
        assert np.array_equal(a["mask"], b["mask"]) and np.array_equal(a["image"], b["image"])
        assert a["command"] == b["command"] and a["technique"] == b["technique"]
