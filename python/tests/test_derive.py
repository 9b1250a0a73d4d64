"""derive from Python is the command's derive, byte for byte, for every example and filter."""
import json

import pytest

import pfgen
from conftest import example_models


@pytest.mark.parametrize("path", example_models())
def test_every_filter_prints_as_the_command(path, pfgen_command):
    model = pfgen.Model.load(path)
    assert model.kinds, path
    listed = pfgen_command.run("derive", path, "--format", "json").stdout
    assert json.loads(listed)["model"] == model.name
    for kind in model.kinds:
        filter_ = model.derive(kind)
        assert filter_.name == kind
        assert filter_.text == pfgen_command.run("derive", path, "--filter", kind).stdout, (path, kind)
        assert filter_.latex == pfgen_command.run("derive", path, "--filter", kind, "--format", "latex").stdout
        command_json = pfgen_command.run("derive", path, "--filter", kind, "--format", "json").stdout
        assert filter_._native.json() == command_json
        assert filter_.json == json.loads(command_json)


def test_default_filter_is_the_commands(pfgen_command):
    path = "examples/basin2006_quadratic.yaml"
    model = pfgen.Model.load(path)
    assert model.derive().text == pfgen_command.run("derive", path).stdout
    assert model.default_kinds == ["optimal", "ekf", "additive", "ekf-additive", "ekf-printed"]
    assert "ukf" in model.kinds and "ukf" not in model.default_kinds


def test_from_yaml_text_is_the_file():
    path = "examples/van_der_pol.yaml"
    with open(path) as f:
        text = f.read()
    from_text = pfgen.Model.from_yaml(text, source="vdp")
    assert from_text.source == "vdp"
    assert from_text.name == pfgen.Model.load(path).name
    assert from_text.derive("optimal").text == pfgen.Model.load(path).derive("optimal").text
    assert from_text.state_names == ["x1", "x2"]
    assert set(from_text.parameter_names) >= {"mu"}


def test_notebook_display_is_the_equations():
    optimal = pfgen.Model.load("examples/basin2006_quadratic.yaml").derive("optimal")
    shown = optimal._repr_latex_()
    assert shown.startswith("\\begin{align*}") and shown.endswith("\\end{align*}")
    assert "dm_{1} &=" in shown and "\\noindent" not in shown
    assert shown in optimal.latex


def test_latex_document_is_the_commands(pfgen_command, work_dir):
    path = "examples/basin2006_quadratic.yaml"
    out = work_dir / "doc.tex"
    pfgen_command.run("latex", path, "--filter", "optimal,ekf", "-o", str(out))
    assert pfgen.Model.load(path).latex_document(["optimal", "ekf"]) == out.read_text()
