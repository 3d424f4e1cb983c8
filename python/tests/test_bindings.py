"""The bindings give what the CLI gives: same reports, counts and output bytes."""
import json

import pytest

import kintsugi
from conftest import without_timings


@pytest.fixture
def paper(tmp_path, cli):
    def make(n):
        path = tmp_path / f"paper{n}.json"
        code, _, err = cli("generate", f"paper-{n}", "-o", path)
        assert code == 0, err
        return path

    return make


@pytest.mark.parametrize("n", [6, 7, 8, 9, 10])
def test_beautify_same_counts_and_bytes_as_cli(n, paper, cli, tmp_path):
    src = paper(n)
    code, _, err = cli("beautify", src, "-o", tmp_path / "cli.json", "--report", tmp_path / "cli-report.json")
    assert code == 0, err
    cli_report = json.loads((tmp_path / "cli-report.json").read_text())

    model = kintsugi.read(str(src))
    report = kintsugi.beautify(model)
    kintsugi.write(model, str(tmp_path / "py.json"), str(src))

    assert report["counts_before"] == cli_report["counts_before"]
    assert report["counts_after"] == cli_report["counts_after"]
    assert report["problems_after"] == cli_report["problems_after"]
    assert without_timings(report) == without_timings(cli_report)
    assert model.counts == report["counts_after"]
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    # paper objects 6-10 need only the implemented passes: something was repaired
    assert any(p["action"] == "repaired" for p in report["problems"])


def test_beautify_file_is_the_cli_verb(paper, cli, tmp_path):
    src = paper(6)
    cli("beautify", src, "-o", tmp_path / "cli.json", "--report", tmp_path / "cli-report.json")
    report = kintsugi.beautify_file(str(src), str(tmp_path / "py.json"))
    assert without_timings(report) == without_timings(json.loads((tmp_path / "cli-report.json").read_text()))
    assert set(report["seconds"]) == {"read", "tolerance", "beautify", "write", "passes"}
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()


def test_detect_and_check_are_the_cli_documents(paper, cli):
    src = paper(7)
    model = kintsugi.read(str(src))
    code, out, _ = cli("detect", src, "--json")
    assert code == 0
    assert kintsugi.detect(model) == json.loads(out)
    code, out, _ = cli("detect", src, "--json", "--tol", "0.05")
    assert kintsugi.detect(model, tol=0.05) == json.loads(out)
    code, out, _ = cli("check", src, "--json")
    assert kintsugi.check(model) == json.loads(out)
    assert kintsugi.check(model)["valid"] is (code == 0)
    problems = kintsugi.detect(model)["problems"]
    assert problems and all(p["elements"] and isinstance(p["elements"][0], str) for p in problems)


def test_model_object(paper):
    model = kintsugi.read(str(paper(6)))
    assert model.format == "json" and model.units
    assert "faces" in repr(model)
    copy = model.copy()
    kintsugi.beautify(model)
    assert copy.counts != model.counts  # the copy was not repaired
    meta = model.meta
    assert meta["tolerance"] > 0 and "defects" not in meta
    model.meta = {"tolerance": 0.5}
    assert model.meta == {"tolerance": 0.5}


def test_errors_name_the_place(tmp_path):
    with pytest.raises(kintsugi.Error, match="nowhere.json"):
        kintsugi.read(str(tmp_path / "nowhere.json"))
    (tmp_path / "bad.json").write_text('{"format": "kintsugi-brep"')
    with pytest.raises(kintsugi.Error, match="bad.json"):
        kintsugi.read(str(tmp_path / "bad.json"))
    with pytest.raises(kintsugi.Error, match="unknown file type"):
        kintsugi.read(str(tmp_path / "x.obj"))


def test_bad_tolerance_raises(paper):
    model = kintsugi.read(str(paper(6)))
    with pytest.raises(kintsugi.Error, match="positive"):
        kintsugi.detect(model, tol=-1.0)
