"""codegen from Python writes the command's files, in memory or in a directory."""
import os

import pfgen

QUADRATIC = "examples/basin2006_quadratic.yaml"


def tree(directory):
    out = {}
    for root, _, files in os.walk(directory):
        for name in files:
            path = os.path.join(root, name)
            with open(path) as f:
                out[os.path.relpath(path, directory)] = f.read()
    return out


def test_every_language_and_scalar_is_the_commands(pfgen_command, work_dir):
    model = pfgen.Model.load(QUADRATIC)
    cases = [("cpp", None, []), ("cpp", "float", ["--scalar", "float", "--eigen"]), ("c", None, ["--language", "c"]),
             ("c", "float", ["--language", "c", "--scalar", "float"])]
    for k, (language, scalar, args) in enumerate(cases):
        out = work_dir / f"command{k}"
        pfgen_command.run("codegen", QUADRATIC, "-o", str(out), *args)
        files = model.codegen(language=language, scalar=scalar, eigen="--eigen" in args)
        assert files == tree(out), args
        written = model.codegen(str(work_dir / f"python{k}"), language=language, scalar=scalar, eigen="--eigen" in args)
        assert tree(work_dir / f"python{k}") == files
        assert sorted(os.path.relpath(p, work_dir / f"python{k}") for p in written) == sorted(files)


def test_named_filters_only(work_dir):
    files = pfgen.Model.load(QUADRATIC).codegen(kinds=["ekf"], language="c")
    assert sorted(files) == ["basin2006_quadratic/ekf.c", "basin2006_quadratic/ekf.h"]


def test_the_model_file_is_never_replaced(work_dir, pfgen_command):
    # A model named like the file that a filter's code would be written to.
    model_file = work_dir / "m" / "optimal.hpp"
    model_file.parent.mkdir()
    with open(QUADRATIC) as f:
        model_file.write_text(f.read().replace("name: basin2006_quadratic", "name: m"))
    before = model_file.read_text()
    model = pfgen.Model.load(str(model_file))
    try:
        model.codegen(str(work_dir))
        raise AssertionError("codegen replaced the model file")
    except pfgen.Error as e:
        assert str(e) == pfgen_command.error_line("codegen", str(model_file), "-o", str(work_dir))
    assert model_file.read_text() == before
