"""The benchmark scripts run, and the two UFOs the fontmake benchmark compares hold the same
font: the filter turns the κ sources into exactly the outlines of the plain UFO."""

import importlib.util
import sys

import pytest

pytest.importorskip("ufo2ft")

import ufoLib2  # noqa: E402
from fontTools.pens.recordingPen import RecordingPen  # noqa: E402

from kappa.ufo2ft import KappaFilter  # noqa: E402

from conftest import PYTHON_DIR, ROOT  # noqa: E402


def load(name):
    spec = importlib.util.spec_from_file_location(name, PYTHON_DIR / "benches" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_bear_benchmark_runs(capsys, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["bear.py", "--repeat", "10"])
    load("bear").main()
    out = capsys.readouterr().out
    assert "bear: 28 curves, 96 points" in out
    assert out.count("µs per pass") == 3


def test_fontmake_benchmark_compares_the_same_font(tmp_path):
    bench = load("fontmake_filter")
    n, _ = bench.build_ufos(ROOT / "tests" / "fonts" / "DejaVuSans.ttf", tmp_path)
    assert n == len(bench.ALPHABET)
    plain = ufoLib2.Font.open(tmp_path / "plain.ufo")
    source = ufoLib2.Font.open(tmp_path / "kappa.ufo")
    assert list(plain.keys()) == list(source.keys())
    assert all(len(source[name]) == 0 for name in source.keys())
    KappaFilter()(source)
    for name in plain.keys():
        a, b = RecordingPen(), RecordingPen()
        plain[name].draw(a)
        source[name].draw(b)
        assert a.value == b.value, name
        assert plain[name].width == source[name].width
