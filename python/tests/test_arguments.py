"""Every argument of the module's calls, given what Python allows: paths as str, bytes or
os.PathLike; None as the default; a value of the wrong type, an int beyond a double, NaN or a
negative count as pfgen.Error naming the option, never another exception or a silent reading."""
import os
import pathlib

import numpy as np
import pytest

import pfgen

QUADRATIC = "examples/basin2006_quadratic.yaml"
BEYOND = "is outside the range of a double (magnitudes from about 2.2e-308 to 1.8e308)"


def refused(call):
    with pytest.raises(pfgen.Error) as error:
        call()
    return str(error.value)


def test_paths_as_str_bytes_or_pathlike(work_dir):
    model = pfgen.Model.load(QUADRATIC)
    for path in (pathlib.Path(QUADRATIC), os.fsencode(QUADRATIC)):
        assert pfgen.Model.load(path).source == QUADRATIC
    files = model.codegen(kinds="ekf")
    for name, directory in (("str", str(work_dir / "str")), ("bytes", os.fsencode(work_dir / "bytes")),
                            ("path", work_dir / "path")):
        written = model.codegen(directory, kinds="ekf")
        assert written == [os.path.join(str(work_dir / name), relative) for relative in files]
        assert all(pathlib.Path(p).read_text() == files[r] for p, r in zip(written, files))
    assert sorted(os.listdir(work_dir)) == ["bytes", "path", "str"]  # no directory named b'bytes'
    assert pfgen.Model.from_yaml(pathlib.Path(QUADRATIC).read_text(), source=pathlib.Path("q.yaml")).source == "q.yaml"
    result = pfgen.simulate(model, runs=1, T=0.1, filters="ekf", cache_dir=os.fsencode(work_dir / "cache"))
    assert result.runs == 1 and (work_dir / "cache").is_dir()


def test_what_is_not_a_path():
    model = pfgen.Model.load(QUADRATIC)
    assert refused(lambda: pfgen.Model.load(None)) == \
        "error: the model file: expected a path (str, bytes or os.PathLike), got NoneType"
    assert refused(lambda: model.codegen(5)) == "error: --output: expected a path (str, bytes or os.PathLike), got int"
    assert refused(lambda: pfgen.simulate(model, cache_dir=1.5)).startswith("error: --cache-dir: expected a path")
    assert refused(lambda: pfgen.simulate(model, compiler=["c++"])).startswith("error: --compiler: expected a path")
    assert refused(lambda: pfgen.Model.load(b"\xff.yaml")) == "error: the model file: b'\\xff.yaml' is not UTF-8: pfgen's paths are"
    assert refused(lambda: pfgen.Model.from_yaml("name: x\n", source=None)).startswith("error: the model's source name")
    assert refused(lambda: pfgen.Model.from_yaml(None)) == "error: the model's text: expected a str, got NoneType"


def test_none_is_the_default():
    model = pfgen.Model.load(QUADRATIC)
    assert model.codegen(namespace=None, language=None, scalar=None, eigen=None) == model.codegen()
    assert model.derive(None).name == "optimal"
    one = pfgen.simulate(model, runs=2, T=0.1, filters="ekf", threads=None, batch=None)
    assert one.csv == pfgen.simulate(model, runs=2, T=0.1, filters="ekf").csv


def test_text_options_take_text():
    model = pfgen.Model.load(QUADRATIC)
    assert refused(lambda: model.codegen(namespace=5)) == "error: --namespace: expected a str, got int 5"
    assert refused(lambda: model.codegen(language=b"c")) == "error: --language: expected a str, got bytes b'c'"
    assert refused(lambda: model.codegen(eigen="no")) == "error: --eigen: expected True or False, got 'no'"
    assert refused(lambda: model.derive(1)) == "error: --filter: expected a str, got int 1"
    assert refused(lambda: model.latex_document(5)) == "error: --filter: expected a filter's name or a list of them, got 5"
    assert refused(lambda: pfgen.simulate(model, filters=3)).startswith("error: --filters: expected a filter's name")
    assert refused(lambda: pfgen.simulate(model, scheme=1)) == "error: --scheme: expected a str, got int 1"
    assert refused(lambda: pfgen.simulate(model, x0=0)) == "error: --x0: expected a str, got int 0"
    assert refused(lambda: pfgen.simulate(model, parameters=[("a", 1)])) == \
        "error: --set: expected a dict of parameter names and numbers, got list"
    assert refused(lambda: pfgen.simulate(model, parameters={1: 2})) == "error: --set: a parameter's name must be a str, got 1"
    with pytest.raises(TypeError, match="expected a pfgen.Model"):
        pfgen.simulate(QUADRATIC)


@pytest.mark.parametrize("big, shown", [(10**400, "'1000000000000000000000000000000000000...'"),
                                        (-10**400, "'-100000000000000000000000000000000000...'"),
                                        (10**5000, "'<an integer of 16610 bits>'")], ids=["1e400", "-1e400", "1e5000"])
def test_ints_beyond_a_double(big, shown):
    model = pfgen.Model.load(QUADRATIC)
    optimal = model.derive("optimal")
    for option, call in (("--t", lambda: optimal.eval(big, [0.5], [[1]])),
                         ("--m", lambda: optimal.eval(0, [big], [[1]])),
                         ("--P", lambda: optimal.eval(0, [0.5], [[1, big]])),
                         ("--set a", lambda: optimal.eval(0, [0.5], [[1]], a=big)),
                         ("--dt", lambda: model.codegen(dt=big)),
                         ("--T", lambda: pfgen.simulate(model, T=big)),
                         ("--bound", lambda: pfgen.simulate(model, bound=big)),
                         ("--report-times", lambda: pfgen.simulate(model, report_times=[1, big])),
                         ("--windows", lambda: pfgen.simulate(model, windows=[(0, big)])),
                         ("--set a", lambda: pfgen.simulate(model, parameters={"a": big}))):
        assert refused(call) == f"error: {option}: {shown} {BEYOND}"


def test_counts_take_whole_numbers_only():
    model = pfgen.Model.load(QUADRATIC)
    for option, name in (("--runs", "runs"), ("--seed", "seed"), ("--reference", "reference"),
                         ("--record-points", "record_points"), ("--shown-run", "shown_run"), ("--threads", "threads")):
        for bad in (-1, 2.0, float("nan"), True, "3", 10**30):
            assert refused(lambda: pfgen.simulate(model, **{name: bad})).startswith(f"error: {option}: "), (name, bad)
    assert pfgen.simulate(model, runs=np.int64(1), T=0.1, filters="ekf").runs == 1


def test_nan_and_inf_as_the_command_refuses_them(pfgen_command):
    model = pfgen.Model.load(QUADRATIC)
    optimal = model.derive("optimal")
    assert refused(lambda: optimal.eval(float("nan"), [0.5], [[1]])) == pfgen_command.error_line(
        "eval", QUADRATIC, "--filter", "optimal", "--t", "nan", "--m", "0.5", "--P", "1")
    assert refused(lambda: optimal.eval(0, [float("inf")], [[1]])) == pfgen_command.error_line(
        "eval", QUADRATIC, "--filter", "optimal", "--m", "inf", "--P", "1")
    assert refused(lambda: pfgen.simulate(model, report_times=[float("nan")])) == "error: --report-times: 'nan' is not a finite number"
    assert refused(lambda: pfgen.simulate(model, windows=[(float("-inf"), 1)])) == "error: --windows: '-inf' is not a finite number"


def test_from_yaml_keeps_the_model_files_bound(pfgen_command, work_dir):
    """70 MB of text is refused as a 70 MB model file is, before the YAML parser spends seconds on it."""
    text = "#" * ((64 << 20) + 1)
    big = work_dir / "big.yaml"
    big.write_text(text)
    message = refused(lambda: pfgen.Model.load(str(big)))
    assert message == f"{big}: error: the model file is larger than 64 MiB: not a model file"
    assert message == pfgen_command.error_line("derive", str(big))
    assert refused(lambda: pfgen.Model.from_yaml(text, source=str(big))) == message
    assert refused(lambda: pfgen.Model.from_yaml(text.encode())) == \
        "<yaml>: error: the model file is larger than 64 MiB: not a model file"
