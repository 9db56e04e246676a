"""Regression: ``derive(scene)`` on a scene with ``[params]`` evaluated the parameters and
silently returned numbers, while ``inertance derive`` takes them as its symbols (README:
"default symbols: the scene's [params]"). Both now take the default from one library function
(``tools::derive::default_symbols``; tests/regression_derive_params_not_symbols.rs)."""

import pytest

import inertance
from conftest import ROOT, cli_json

BOX = ROOT / "examples" / "tilted-box.toml"


@pytest.mark.parametrize("given", ["scene", "path", "text"])
def test_derive_takes_the_params_as_symbols_like_the_cli(given):
    scene = {"scene": inertance.Scene.load(BOX), "path": str(BOX), "text": BOX.read_text()}[given]
    d = inertance.derive(scene, model="newton")
    assert d.json["symbols"] == ["theta"]
    assert "cos(theta)" in d.json["models"]["newton"]["impulses"][0]
    assert d.json == cli_json("derive", BOX, "--model", "newton")


def test_named_symbols_still_win():
    d = inertance.derive(BOX, symbols=["theta"], model="newton")
    assert d.json["symbols"] == ["theta"]


def test_a_scene_without_params_or_symbols_is_refused():
    bar = inertance.Scene.load(ROOT / "examples" / "planar-bar.toml")
    with pytest.raises(inertance.SceneError) as e:
        inertance.derive(bar)
    assert e.value.key == "params" and "symbols=" in e.value.message
