"""Bad input raises pfgen.Error, and only it, with the command's message."""
import pytest

import pfgen

QUADRATIC = "examples/basin2006_quadratic.yaml"


def refused(call):
    with pytest.raises(pfgen.Error) as error:
        call()
    return str(error.value)


def test_a_bad_model_file(pfgen_command, work_dir):
    bad = work_dir / "bad.yaml"
    bad.write_text("name: bad\nstates: [x]\ndrift: [x^2 +]\ndiffusion: [[1]]\nobservation: {A: [[1]], B: [[1]]}\n")
    message = refused(lambda: pfgen.Model.load(str(bad)))
    assert message == pfgen_command.error_line("derive", str(bad))
    assert message.startswith(f"{bad}:3:")
    assert refused(lambda: pfgen.Model.load(str(work_dir / "missing.yaml"))) == \
        pfgen_command.error_line("derive", str(work_dir / "missing.yaml"))
    text = bad.read_text()
    assert refused(lambda: pfgen.Model.from_yaml(text, source=str(bad))) == message


def test_an_unknown_filter(pfgen_command):
    model = pfgen.Model.load(QUADRATIC)
    assert refused(lambda: model.derive("kalman")) == pfgen_command.error_line("derive", QUADRATIC, "--filter", "kalman")


def test_a_bad_point(pfgen_command):
    optimal = pfgen.Model.load(QUADRATIC).derive("optimal")
    assert refused(lambda: optimal.eval(0, [1, 2], [[1]])) == \
        pfgen_command.error_line("eval", QUADRATIC, "--filter", "optimal", "--m", "1,2", "--P", "1")
    assert refused(lambda: optimal.eval(0, [1], [[-1]])) == \
        pfgen_command.error_line("eval", QUADRATIC, "--filter", "optimal", "--m", "1", "--P", "-1")
    van_der_pol = "examples/van_der_pol.yaml"
    vdp = pfgen.Model.load(van_der_pol).derive("optimal")
    assert refused(lambda: vdp.eval(0, [1, 0], [[1, 0], [0, 1]], nu=2)) == pfgen_command.error_line(
        "eval", van_der_pol, "--filter", "optimal", "--m", "1,0", "--P", "1,0;0,1", "--set", "nu=2")
    assert refused(lambda: vdp.eval(0, [1, 0], [[1, 0], [0, 1]], r=0)) == pfgen_command.error_line(
        "eval", van_der_pol, "--filter", "optimal", "--m", "1,0", "--P", "1,0;0,1", "--set", "r=0")


def test_bad_codegen_options(pfgen_command, work_dir):
    model = pfgen.Model.load(QUADRATIC)
    out = str(work_dir / "out")
    assert refused(lambda: model.codegen(out, language="c", scalar="template")) == pfgen_command.error_line(
        "codegen", QUADRATIC, "--language", "c", "--scalar", "template", "-o", out)
    assert refused(lambda: model.codegen(out, namespace="a::2b")) == pfgen_command.error_line(
        "codegen", QUADRATIC, "--namespace", "a::2b", "-o", out)
    assert refused(lambda: model.codegen(out, kinds=["optimal", "nope"])) == pfgen_command.error_line(
        "codegen", QUADRATIC, "--filter", "optimal,nope", "-o", out)
    assert refused(lambda: model.codegen(language="fortran")).startswith("error: --language: fortran not in {cpp,c,rust}")


def test_bad_simulation_settings(pfgen_command):
    model = pfgen.Model.load(QUADRATIC)
    assert refused(lambda: pfgen.simulate(model, runs=0)) == pfgen_command.error_line(
        "simulate", QUADRATIC, "--runs", "0")
    assert refused(lambda: pfgen.simulate(model, T=1, dt=2)) == pfgen_command.error_line(
        "simulate", QUADRATIC, "--T", "1", "--dt", "2")
    assert refused(lambda: pfgen.simulate(model, filters=["optimal", "kalman"])) == pfgen_command.error_line(
        "simulate", QUADRATIC, "--filters", "optimal,kalman")
    assert refused(lambda: pfgen.simulate(model, runs=2, T=1, reference=0)) == pfgen_command.error_line(
        "simulate", QUADRATIC, "--runs", "2", "--T", "1", "--reference", "particles:0")
    assert refused(lambda: pfgen.simulate(model, parameters={"zz": 1})) == pfgen_command.error_line(
        "simulate", QUADRATIC, "--set", "zz=1")


def test_nothing_else_is_raised():
    # Wrong Python types are Python's TypeError before pfgen is called; everything pfgen
    # refuses is pfgen.Error, an Exception.
    assert issubclass(pfgen.Error, Exception)
    with pytest.raises(pfgen.Error):
        pfgen.Model.from_yaml("[")
    with pytest.raises(pfgen.Error):
        pfgen.Model.from_yaml("name: x\n")


def test_values_python_cannot_give_as_text():
    model = pfgen.Model.load(QUADRATIC)
    optimal = model.derive("optimal")
    assert refused(lambda: optimal.eval(0, [0.5], [[1, 0], [0]])) == "error: --P: expected a matrix of numbers, row by row"
    assert refused(lambda: optimal.eval(0, ["a"], [[1]])) == "error: --m: expected a vector of numbers"
    assert refused(lambda: optimal.eval(0, [0.5], None)) == "error: --P is required"
    assert refused(lambda: pfgen.simulate(model, runs=-1)) == \
        "error: --runs: '-1' is not a whole number from 0 to 18446744073709551615"
    assert refused(lambda: pfgen.simulate(model, runs=1.5)).startswith("error: --runs: '1.5' is not a whole number")
    assert refused(lambda: pfgen.simulate(model, windows=[(0, 0.1, 0.2)])) == \
        "error: --windows: expected (a, b) pairs of numbers"
    for call in (lambda: pfgen.Model.load(QUADRATIC + "\0x"), lambda: model.derive("optimal\0"),
                 lambda: model.codegen("out\0x"), lambda: pfgen.simulate(model, cache_dir="c\0x")):
        assert "is followed by a NUL character" in refused(call)


def test_numbers_out_of_range_as_the_command_says(pfgen_command):
    model = pfgen.Model.load(QUADRATIC)
    for value, text in ((float("nan"), "nan"), (5e-324, "5e-324")):
        line = pfgen_command.error_line("simulate", QUADRATIC, "--T", text)
        assert line.endswith(" (see pfgen --help)")
        assert refused(lambda: pfgen.simulate(model, T=value)) == line[:-len(" (see pfgen --help)")]


def test_an_endless_model_file_is_refused(pfgen_command):
    message = refused(lambda: pfgen.Model.load("/dev/zero"))
    assert message == "/dev/zero: error: the model file is larger than 64 MiB: not a model file"
    assert message == pfgen_command.error_line("derive", "/dev/zero")


def test_a_huge_point_is_refused_before_it_is_read():
    optimal = pfgen.Model.load(QUADRATIC).derive("optimal")
    import numpy as np
    assert refused(lambda: optimal.eval(0, [0.5], np.eye(2000))) == "error: --P: expected 1 rows, found 2000"


def test_as_the_command_reads_its_filter_lists(pfgen_command, work_dir):
    model = pfgen.Model.load(QUADRATIC)
    # No name is the model's first filter, as the command without --filter (whose `--filter ""`,
    # an empty list given, it refuses).
    assert model.derive("").text == model.derive().text == pfgen_command.run("derive", QUADRATIC).stdout
    out = str(work_dir / "out")
    assert refused(lambda: model.codegen(kinds=["optimal", "optimal"])).startswith("error: -o (filter optimal)")
    assert refused(lambda: model.codegen(out, kinds=["optimal", "optimal"])) == pfgen_command.error_line(
        "codegen", QUADRATIC, "--filter", "optimal,optimal", "-o", out)
    assert sorted(model.codegen(kinds="ekf", language="c")) == ["basin2006_quadratic/ekf.c", "basin2006_quadratic/ekf.h"]
