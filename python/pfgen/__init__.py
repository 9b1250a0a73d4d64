"""pfgen: Gaussian-closure filters of polynomial stochastic systems, derived exactly.

The same engine as the ``pfgen`` command, called in process: every function gives what the
matching command prints and fails with the same message (docs/guide/python.md).

    import pfgen
    model = pfgen.Model.load("examples/basin2006_quadratic.yaml")
    optimal = model.derive("optimal")
    optimal                      # in Jupyter: the equations, as LaTeX
    print(optimal.text)          # pfgen derive --filter optimal
    optimal.eval(0, [0.5], [[1]])  # pfgen eval: {"m_drift": array([0.125]), ...}
    result = pfgen.simulate(model, runs=100, T=1, reference=1000)
    print(result.report)         # pfgen simulate's table
    run = pfgen.estimate(model, "record.csv")   # pfgen estimate --data record.csv
    run.filters["optimal"].m     # the estimates at the data times, a numpy array
"""
import importlib as _importlib
import json as _json
import os as _os
import platform as _platform
import re as _re
import sys as _sys
import threading as _threading

from . import _built_for


def _import_hint(error):
    """Why pfgen cannot be imported here, naming the interpreter it was built for: a python3
    earlier on PATH than Debian's (pyenv's, a venv's) has neither its numpy nor, often, its ABI."""
    built, here = _built_for.INTERPRETER, _sys.executable or "this interpreter"
    try:
        same = _os.path.samefile(built, here)
    except OSError:
        same = False
    if same:
        return (f"pfgen cannot be imported: {error}. It was built for this interpreter, {built}; its "
                "numpy is Debian's python3-numpy (scripts/install-deps.sh installs it)")
    return (f"pfgen cannot be imported by {here} (Python {_platform.python_version()}): {error}. pfgen was "
            f"built for {built} (Python {_built_for.VERSION}), for which the set-up installs numpy: run "
            f"that interpreter ({built} script.py), or build pfgen for this one (cmake "
            f"-DPython3_EXECUTABLE={here}) with numpy installed for it")


try:
    import numpy as _np

    from . import _pfgen
except ImportError as _error:
    raise ImportError(_import_hint(_error)) from _error

__all__ = ["Error", "Model", "Filter", "Simulation", "simulate", "Estimate", "FilterRun", "estimate", "Fit", "fit",
           "__version__"]
__version__ = _pfgen.version()

#: The one exception pfgen raises for a bad model, option, point or file. Its message is the line
#: the command prints after "pfgen: " ("m.yaml:4:15: error: ..." or "error: ...").
Error = _pfgen.Error


def _shown(value):
    """A value as a message shows it: its repr, shortened (an int of 10**5000 has no repr)."""
    try:
        text = repr(value)
    except ValueError:
        return f"<an integer of {value.bit_length()} bits>"
    return text if len(text) <= 40 else text[:37] + "..."


def _out_of_range(option, value):
    """A Python int beyond a double's range, in the words of the command's own check."""
    return Error(f"error: {option}: '{_shown(value)}' is outside the range of a double "
                 "(magnitudes from about 2.2e-308 to 1.8e308)")


def _float_array(values, option):
    """numpy's float array of `values`; an int beyond a double's range, or a complex value (which
    numpy would cut to its real part with a warning), is pfgen's Error."""
    # numpy's own reading of a list says whether it holds a complex value; only a list it reads as
    # objects (None, ints beyond int64 beside them) is looked through one by one.
    try:
        read = values if isinstance(values, _np.ndarray) else _np.asarray(values)
    except (ValueError, TypeError):
        read = None  # ragged or unreadable: the conversion below says so, as before
    if read is not None and (read.dtype.kind == "c" or
                             (read.dtype.kind == "O" and any(isinstance(v, complex) for v in read.ravel()))):
        raise Error(f"error: {option}: complex values are not read: give real numbers")
    try:
        return _np.asarray(values, dtype=float)
    except OverflowError:
        big = next((v for v in _np.asarray(values, dtype=object).ravel() if not _fits(v)), values)
        raise _out_of_range(option, big) from None


def _fits(value):
    try:
        float(value)
    except OverflowError:
        return False
    except (TypeError, ValueError):
        pass
    return True


def _number_list(values, option):
    """A number or a sequence of numbers (or a numpy array) as a list of floats."""
    if values is None:
        return []
    try:
        array = _float_array(values, option)
    except (TypeError, ValueError):
        raise Error(f"error: {option}: expected a vector of numbers") from None
    if array.ndim == 0:
        array = array.reshape(1)
    if array.ndim != 1:
        raise Error(f"error: {option}: expected a vector of numbers, got an array of shape {array.shape}")
    return [float(v) for v in array]


def _number_matrix(values, option):
    if values is None:
        raise Error(f"error: {option} is required")
    try:
        array = _float_array(values, option)
    except (TypeError, ValueError):
        raise Error(f"error: {option}: expected a matrix of numbers, row by row") from None
    if array.ndim == 0:  # one state: P may be given as a number
        array = array.reshape(1, 1)
    if array.ndim != 2:
        raise Error(f"error: {option}: expected a matrix of numbers, got an array of shape {array.shape}")
    return [[float(v) for v in row] for row in array]


def _number(value, option):
    try:
        return float(value)
    except OverflowError:
        raise _out_of_range(option, value) from None
    except (TypeError, ValueError):
        raise Error(f"error: {option}: {_shown(value)} is not a number") from None


def _optional_number(value, option):
    return None if value is None else _number(value, option)


_MAX_UINT64 = 2**64 - 1


def _whole(value, option, maximum=_MAX_UINT64):
    """A count or a seed, as the command line reads its whole-number options."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)) or not 0 <= value <= maximum:
        raise Error(f"error: {option}: {str(value)!r} is not a whole number from 0 to {maximum}")
    return int(value)


def _names(names, option, what="a filter's name"):
    """Names (of filters, columns, parameters): a list, or one name as a string."""
    if names is None:
        return []
    if isinstance(names, str):
        return [names]
    try:
        names = list(names)
    except TypeError:
        raise Error(f"error: {option}: expected {what} or a list of them, got {_shown(names)}") from None
    for name in names:
        if not isinstance(name, str):
            raise Error(f"error: {option}: {_shown(name)} is not {what}")
    return names


def _path(value, option):
    """A path as open() takes one: str, bytes (decoded as os.fsdecode does) or os.PathLike. pfgen's
    paths are UTF-8 text, as its messages and the generated files' names are."""
    try:
        path = _os.fsdecode(value)
    except TypeError:
        raise Error(f"error: {option}: expected a path (str, bytes or os.PathLike), got {type(value).__name__}") from None
    try:
        path.encode("utf-8")
    except UnicodeEncodeError:
        raise Error(f"error: {option}: {_shown(value)} is not UTF-8: pfgen's paths are") from None
    return path


def _text(value, option, default):
    """An option's text (a str); None gives the option's default."""
    if value is None:
        return default
    if not isinstance(value, str):
        raise Error(f"error: {option}: expected a str, got {type(value).__name__} {_shown(value)}")
    return value


def _optional_module(name, package, call):
    """An optional module a call needs, or an ImportError naming the Debian package that gives it."""
    try:
        return _importlib.import_module(name)
    except ImportError as e:
        raise ImportError(f"{call} needs {name}, which this Python cannot import "
                          f"(Debian: apt-get install {package}): {e}") from e


def _parameters(values):
    """Parameters' new values, name -> number, as --set name=value gives them."""
    return _assignments(values, "--set", "parameter")


def _assignments(values, option, what):
    """Named numbers, name -> number, as the command's `option` name=value gives them (--set, --moment)."""
    if values is None:
        return {}
    try:
        items = list(values.items())
    except (AttributeError, TypeError):
        raise Error(f"error: {option}: expected a dict of {what} names and numbers, "
                    f"got {type(values).__name__}") from None
    out = {}
    for name, value in items:
        if not isinstance(name, str):
            raise Error(f"error: {option}: a {what}'s name must be a str, got {_shown(name)}")
        out[name] = _number(value, f"{option} {name}")
    return out


def _arrays(value):
    """eval's JSON with its lists of numbers as numpy arrays (its objects stay dicts, its lists of names
    lists: a moment filter's "moments")."""
    if isinstance(value, dict):
        return {key: _arrays(item) for key, item in value.items()}
    if isinstance(value, list) and value and all(isinstance(item, str) for item in value):
        return list(value)
    return _np.array(value, dtype=float)


class Filter:
    """One derived filter: its equations as text, LaTeX, JSON and SymPy, and its values at a point."""

    def __init__(self, model, native):
        self._model = model
        self._native = native
        self._text = self._latex = None

    @property
    def name(self):
        """The filter's name: "optimal", "ekf-additive", or a user filter's."""
        return self._native.name

    @property
    def model(self):
        return self._model

    @property
    def text(self):
        """What ``pfgen derive --filter NAME`` prints."""
        if self._text is None:
            self._text = self._native.text()
        return self._text

    @property
    def latex(self):
        """What ``pfgen derive --filter NAME --format latex`` prints."""
        if self._latex is None:
            self._latex = self._native.latex()
        return self._latex

    @property
    def json(self):
        """``pfgen derive --filter NAME --format json``, as a dict."""
        return _json.loads(self._native.json())

    def _repr_latex_(self):
        # Jupyter renders math, not a LaTeX document's text: the equations' align* blocks.
        blocks = _re.findall(r"\\begin\{align\*\}.*?\\end\{align\*\}", self.latex, flags=_re.S)
        return "\n".join(blocks) if blocks else None

    def __repr__(self):
        return f"<pfgen.Filter {self.name} of model {self._model.name}>"

    def eval(self, t, m, P, /, *, m_delayed=None, x_star=None, x_star_delayed=None, phi=None, moments=None,
             parameters=None, **more_parameters):
        """The filter's values at (t, m, P), with parameters given new values by keyword (or in
        ``parameters``, for one named like an argument of eval, such as phi):
        ``pfgen eval --t T --m M --P P --set name=value``. A moment filter (closure3, closure4)
        reads its central moments above P from ``moments``, name -> number (``{"M3_111": 0.2}``,
        ``--moment M3_111=0.2``); one left out takes its value under N(m, P). Returns the command's
        JSON without model and filter, each list of numbers a numpy array: m_drift, gain, P_drift
        (a sampled filter's under "prediction" and "update", a delayed filter's inputs under
        "delayed_inputs"); a polynomial observation's or a moment filter's P_gain (p x n x n: dP's
        coefficients of dy_r - predicted_observation_r dt); a moment filter's "moments" (their
        names, a list), "moment_drift" (one per moment) and "moment_gain" (one row of p per moment),
        or for a sampled one (cd-closure3, cd-closure4) "P_after_update" and "moments_after_update"
        (after an update at the point) in place of "moment_gain"."""
        values = _parameters(parameters)
        values.update(_parameters(more_parameters))
        native = self._native.eval(
            _number(t, "--t"), _number_list(m, "--m"), _number_matrix(P, "--P"), values,
            _number_list(m_delayed, "--m-delayed"), _number_list(x_star, "--x-star"),
            _number_list(x_star_delayed, "--x-star-delayed"), _number_list(phi, "--phi"),
            _assignments(moments, "--moment", "moment"))
        values = _json.loads(native.json)
        return {key: _arrays(value) for key, value in values.items() if key not in ("model", "filter")}

    def run(self, data, **settings):
        """pfgen.estimate(model, data, filters=[this filter], ...): this filter over a record; its
        arrays are ``run(...).filters[name]``."""
        return estimate(self._model, data, filters=[self.name], **settings)

    def to_sympy(self):
        """The equations as SymPy matrices, equal to the printed ones:

            dm = m_drift dt + gain (dy - predicted_observation dt),   dP = P_drift dt

        (a sampled filter's m_drift and P_drift are its prediction between samples, and its gain
        is empty; a polynomial observation's or a moment filter's dP adds sum_r P_gain[r] (dy_r -
        predicted_observation_r dt); a moment filter carries its central moments above P too, each
        dM_q = moment_drift[q] dt + sum_r moment_gain[q, r] (dy_r - predicted_observation_r dt)).
        Returns a SympyFilter with m_drift (n x 1), gain (n x p), P_drift (n x n),
        predicted_observation (p x 1), P_gain (p matrices n x n), moment_names (M3_111, ...),
        moment_drift (q x 1), moment_gain (q x p), definitions (name -> expression, in order) and
        symbols (name -> Symbol: m1, P11, ..., M3_111, ..., the parameters, the time)."""
        sympy = _optional_module("sympy", "python3-sympy", "Filter.to_sympy")
        e = self._native.expressions()
        # Every name as a plain Symbol, so that a parameter called gamma or E stays a symbol; in
        # the text each name is first replaced by a placeholder, since a name such as lambda is a
        # Python keyword, which sympify cannot read.
        symbols = {name: sympy.Symbol(name) for name in e.names}
        placeholders = {name: f"_pfgen_{k}" for k, name in enumerate(e.names)}
        local = {placeholders[name]: symbol for name, symbol in symbols.items()}

        def parse(text):
            # Names only: not the e of a number's exponent (1e-05), which follows a digit.
            text = _re.sub(r"(?<![0-9.A-Za-z_])[A-Za-z_][A-Za-z0-9_]*",
                           lambda w: placeholders.get(w.group(0), w.group(0)), text)
            # The text output's decimals (0.1) read as the exact rationals they stand for.
            return sympy.sympify(text, locals=local, rational=True)

        n = len(e.m_drift)
        p = len(e.gain[0]) if n and e.gain and e.gain[0] else 0
        return SympyFilter(
            m_drift=sympy.Matrix(n, 1, [parse(x) for x in e.m_drift]),
            gain=sympy.Matrix(n, p, [parse(x) for row in e.gain for x in row]),
            P_drift=sympy.Matrix(n, n, [parse(x) for row in e.P_drift for x in row]),
            predicted_observation=sympy.Matrix(len(e.predicted_observation), 1,
                                               [parse(x) for x in e.predicted_observation]),
            definitions={name: parse(value) for name, value in e.definitions},
            symbols=symbols,
            P_gain=[sympy.Matrix(n, n, [parse(x) for row in L for x in row]) for L in e.P_gain],
            moment_names=list(e.moment_names),
            moment_drift=sympy.Matrix(len(e.moment_drift), 1, [parse(x) for x in e.moment_drift]),
            moment_gain=sympy.Matrix(len(e.moment_gain), p, [parse(x) for row in e.moment_gain for x in row]))


class SympyFilter:
    """Filter.to_sympy's result."""

    def __init__(self, m_drift, gain, P_drift, predicted_observation, definitions, symbols, P_gain, moment_names,
                 moment_drift, moment_gain):
        self.m_drift, self.gain, self.P_drift = m_drift, gain, P_drift
        self.predicted_observation, self.definitions, self.symbols = predicted_observation, definitions, symbols
        #: a polynomial observation's (or a moment filter's) dP = P_drift dt + sum_r P_gain[r] (dy_r -
        #: predicted_observation_r dt); empty for the other filters
        self.P_gain = P_gain
        #: a moment filter's central moments above P, in its state's order (M3_111, ..., then M4_...);
        #: dM_q = moment_drift[q] dt + sum_r moment_gain[q, r] (dy_r - predicted_observation_r dt).
        #: Empty (0 rows) for the other filters; a sampled filter's moment_gain has no columns.
        self.moment_names, self.moment_drift, self.moment_gain = moment_names, moment_drift, moment_gain

    def __repr__(self):
        return f"SympyFilter(m_drift={self.m_drift}, gain={self.gain}, P_drift={self.P_drift})"


class Model:
    """A checked model: from a model file (load), YAML text (from_yaml)."""

    def __init__(self, native):
        self._native = native

    @staticmethod
    def load(path):
        """Reads and checks a model file (as every command does); path: str, bytes or os.PathLike."""
        return Model(_pfgen.Model.load(_path(path, "the model file")))

    @staticmethod
    def from_yaml(text, source="<yaml>"):
        """Reads a model from YAML text (str, or UTF-8 bytes), at most 64 MiB as a model file;
        ``source`` names it in messages."""
        if not isinstance(text, (str, bytes)):
            raise Error(f"error: the model's text: expected a str, got {type(text).__name__}")
        return Model(_pfgen.Model.from_yaml(text, _path(source, "the model's source name")))

    name = property(lambda self: self._native.name)
    source = property(lambda self: self._native.source, doc="The file's path, or from_yaml's source.")
    state_names = property(lambda self: self._native.state_names)
    parameter_names = property(lambda self: self._native.parameter_names)
    kinds = property(lambda self: self._native.kinds,
                     doc="Every filter the model offers: the kinds it supports, then its own filters.")
    default_kinds = property(lambda self: self._native.default_kinds,
                             doc="The filters the commands use when none is named (all but the ukf).")

    def __repr__(self):
        return f"<pfgen.Model {self.name} ({self.source})>"

    def derive(self, kind=None):
        """Derives one filter (``pfgen derive --filter KIND``; by default the model's first)."""
        return Filter(self, self._native.derive(_text(kind, "--filter", "")))

    def latex_document(self, kinds=None):
        """``pfgen latex``: a LaTeX document with these filters (default: the default ones)."""
        return self._native.latex_document(_names(kinds, "--filter"))

    def codegen(self, directory=None, kinds=None, scalar=None, language="cpp", namespace="pfgen_models",
                eigen=False, dt=None):
        """``pfgen codegen``: the filters' code in C++ or C (language "cpp" or "c"), with scalar
        "template" (C++), "float" or "double" (default: C++ template, C double). With a directory,
        the files are written there (all or none) and their paths returned; without, a dict from
        each file's relative path to its text. A setting left at None takes its default."""
        options = _pfgen.CodegenOptions()
        options.filters = _names(kinds, "--filter")
        options.language = _text(language, "--language", "cpp")
        options.scalar = _text(scalar, "--scalar", "")
        options.name_space = _text(namespace, "--namespace", "pfgen_models")
        if not isinstance(eigen, (bool, _np.bool_)) and eigen is not None:
            raise Error(f"error: --eigen: expected True or False, got {_shown(eigen)}")
        options.eigen = bool(eigen)
        options.dt = _optional_number(dt, "--dt")
        if directory is None:
            return {f.path: f.contents for f in self._native.codegen_files(options)}
        return self._native.codegen_to(_path(directory, "--output"), options)

    def simulate(self, **settings):
        """pfgen.simulate(self, ...)."""
        return simulate(self, **settings)

    def estimate(self, data, **settings):
        """pfgen.estimate(self, data, ...)."""
        return estimate(self, data, **settings)

    def fit(self, data, estimate, **settings):
        """pfgen.fit(self, data, estimate, ...)."""
        return fit(self, data, estimate, **settings)


class Simulation:
    """What ``pfgen simulate`` computes: the report (its table), the time series of its CSV as
    numpy arrays, and a summary per filter (and the particle reference)."""

    def __init__(self, native, model):
        self.model_name = model.name           #: the model's name, which the plot's title gives
        self.state_names = model.state_names   #: the states, as summary's arrays and the series order them
        self.shown_run = native.shown_run      #: the run whose truth, estimates and errors the series show
        #: the particle reference's N (0 without one)
        self.reference_particles = native.reference_particles
        self.report = native.report    #: the command's standard output, before the paths of files
        self.notes = native.notes      #: what it says on stderr ("pfgen: note: ...")
        self.csv = native.csv          #: the CSV ``-o`` writes
        self.runs = native.runs
        self.steps = native.steps
        #: column name -> numpy array, one value per recorded time (NaN where the CSV is empty)
        self.series = {name: _np.array(values, dtype=float) for name, values in zip(native.columns, native.series)}
        #: filter name -> dict of completed, diverged, psd_losses, unrealisable (a moment filter's runs
        #: stopped where its moments left the realisable set, among diverged), too_stiff and undefined
        #: (runs stopped for want of sub-steps, or where the equations were not finite: among diverged),
        #: rms, rms_se, peak_median,
        #: peak_q95, reference_distance, reference_distance_se, own_error (per state: numpy arrays;
        #: own_error, the particle reference's own Monte Carlo error, in the "reference" entry only)
        self.summary = {}
        for f in native.filters:
            self.summary[f.name] = {
                "completed": f.completed, "diverged": f.diverged, "psd_losses": f.psd_losses,
                "unrealisable": f.unrealisable, "too_stiff": f.too_stiff, "undefined": f.undefined,
                "rms": _np.array(f.rms), "rms_se": _np.array(f.rms_se),
                "peak_median": _np.array(f.peak_median), "peak_q95": _np.array(f.peak_q95),
                "reference_distance": _np.array(f.reference_distance),
                "reference_distance_se": _np.array(f.reference_distance_se),
                "own_error": _np.array(f.own_error)}

    @property
    def t(self):
        return self.series["t"]

    def to_pandas(self, table="summary"):
        """The summary as a pandas DataFrame, one row per filter and state (index: filter, state),
        or with table="series" the series, one row per recorded time (index: t). Needs pandas."""
        return _simulation_frame(self, table)

    def plot(self, ylim=None):
        """``pfgen simulate --plot``'s panels as a matplotlib Figure (not shown: in Jupyter a cell
        ending with it draws it; fig.savefig(path) writes it). Per state, the shown run's errors
        x - m of every filter (and the particle reference's, dashed), then each filter's median
        error over the runs with its 5-95 % band. ylim=Y: the y range [-Y, Y] (--plot-ylim).
        Needs matplotlib."""
        return _simulation_figure(self, ylim)

    def __repr__(self):
        return self.report


def _simulation_frame(simulation, table):
    """Simulation.to_pandas."""
    pandas = _optional_module("pandas", "python3-pandas", "Simulation.to_pandas")
    if table == "series":
        frame = pandas.DataFrame({name: values for name, values in simulation.series.items() if name != "t"},
                                 index=pandas.Index(simulation.t, name="t"))
        return frame
    if table != "summary":
        raise Error(f"error: to_pandas: table is 'summary' or 'series', not {_shown(table)}")
    states = simulation.state_names
    rows, index = [], []
    for name, values in simulation.summary.items():
        for i, state in enumerate(states):
            row = {}
            for key, value in values.items():
                array = _np.asarray(value)
                # Per state where the value has one (an empty array: none for this filter).
                row[key] = (array[i] if len(array) == len(states) else _np.nan) if array.ndim else value
            rows.append(row)
            index.append((name, state))
    return pandas.DataFrame(rows, index=pandas.MultiIndex.from_tuples(index, names=["filter", "state"]))


# The --plot styles (runtime/src/gnuplot_plot.cpp): Okabe-Ito colours; per filter its own dash
# and a width from the widest (the first, drawn first) to the narrowest, so that coinciding curves
# each show; the particle reference black and dashed, on top.
_PLOT_COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"]
_PLOT_DASHES = ["-", (0, (6, 2, 1, 2)), (0, (6, 2, 1, 2, 1, 2)), (0, (8, 2)), (0, (1, 2)), (0, (8, 2, 2, 2)),
                (0, (12, 2, 1, 2, 1, 2)), (0, (4, 2, 2, 2))]
_PLOT_WIDEST, _PLOT_NARROWEST = 3.0, 1.0  # matplotlib's points: gnuplot's widths 6 and 2, halved


def _plot_style(f, count, width=None):
    if width is None:
        width = _PLOT_NARROWEST if count < 2 else _PLOT_WIDEST - (_PLOT_WIDEST - _PLOT_NARROWEST) * f / (count - 1)
    return {"color": _PLOT_COLORS[f % 8], "linestyle": _PLOT_DASHES[f % 8], "linewidth": width}


def _simulation_figure(simulation, ylim):
    """Simulation.plot: the gnuplot script's panels (pfgen_runtime::gnuplot_error_script)."""
    _optional_module("matplotlib", "python3-matplotlib", "Simulation.plot")
    from matplotlib.figure import Figure  # no pyplot: no GUI backend, nothing shown twice in Jupyter
    if ylim is not None:
        ylim = _number(ylim, "--plot-ylim")
        if not (ylim >= 0 and _np.isfinite(ylim)):
            raise Error(f"error: --plot-ylim: {_shown(ylim)} is not a finite number >= 0")
    series, t = simulation.series, simulation.t
    filters = [name for name in simulation.summary if name != "reference"]
    count, states = len(filters), simulation.state_names
    clipped = f" (clipped at +-{ylim:g})" if ylim else ""
    figure = Figure(figsize=(10, 3.6 * 2 * len(states)), layout="constrained")
    figure.suptitle(f"{simulation.model_name}: estimation errors x - m")
    axes = figure.subplots(2 * len(states), 1, squeeze=False)[:, 0]
    for i, x in enumerate(states):
        shown, bands = axes[2 * i], axes[2 * i + 1]
        shown.set_title(f"{x}: run {simulation.shown_run}{clipped}")
        for f, name in enumerate(filters):
            shown.plot(t, series[f"{name}_err_{x}"], label=name, **_plot_style(f, count))
        if simulation.reference_particles and filters:
            shown.plot(t, series[f"reference_err_{x}"], color="#000000", linestyle="--", linewidth=0.75,
                       label=f"reference (N={simulation.reference_particles})")
        bands.set_title(f"{x}: median over {simulation.runs} runs, 5-95 % band{clipped}")
        for f, name in enumerate(filters):
            low, high = series[f"{name}_err_{x}_q05"], series[f"{name}_err_{x}_q95"]
            if f == 0:  # the first band filled, the others' edges only: bands that coincide stay apart
                bands.fill_between(t, low, high, color=_PLOT_COLORS[0], alpha=0.2, linewidth=0, label=f"{name} 5-95 %")
                continue
            bands.plot(t, low, label=f"{name} 5-95 %", **_plot_style(f, count, 0.5))
            bands.plot(t, high, **_plot_style(f, count, 0.5))
        for f, name in enumerate(filters):
            bands.plot(t, series[f"{name}_err_{x}_q50"], label=name, **_plot_style(f, count))
        for panel in (shown, bands):
            panel.set_xlabel("t")
            panel.set_ylabel(f"{x} - m")
            panel.set_xlim(t[0], t[-1])
            if ylim:
                panel.set_ylim(-ylim, ylim)
            panel.grid(True)
            if panel.get_legend_handles_labels()[0]:
                panel.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=min(4, max(1, len(filters))),
                             frameon=False, handlelength=4)
    return figure


def simulate(model, runs=None, T=None, dt=None, filters=None, seed=None, threads=0, reference=None, *,
             scheme=None, x0=None, stepping=None, record_points=None, shown_run=None, bound=None, risk_epsilon=None,
             report_times=None, windows=None, parameters=None, cache_dir=None, compiler=None, batch=8,
             progress=False):
    """``pfgen simulate``: the model's filters (or ``filters``) against simulated truths in Monte
    Carlo, with the particle reference of ``reference`` particles. Unset settings come from the
    model's simulation: section, then pfgen's defaults. The GIL is released while it runs.
    progress=True writes the command's progress line to sys.stderr while it runs (or give a
    text stream)."""
    if not isinstance(model, Model):
        raise TypeError(f"pfgen.simulate: expected a pfgen.Model (pfgen.Model.load(path)), got {type(model).__name__}")
    options = _pfgen.SimulationOptions()
    options.runs = _whole(runs, "--runs")
    options.T = _optional_number(T, "--T")
    options.dt = _optional_number(dt, "--dt")
    options.filters = _names(filters, "--filters")
    options.seed = _whole(seed, "--seed")
    options.threads = _whole(0 if threads is None else threads, "--threads", 2**32 - 1)
    options.batch = _whole(8 if batch is None else batch, "--batch", 2**64 - 1)
    options.reference = _whole(reference, "--reference")
    options.scheme = _text(scheme, "--scheme", None)
    options.x0 = _text(x0, "--x0", None)
    options.stepping = _text(stepping, "--stepping", None)
    options.record_points = _whole(record_points, "--record-points")
    options.shown_run = _whole(shown_run, "--shown-run")
    options.bound = _optional_number(bound, "--bound")
    options.risk_epsilon = _optional_number(risk_epsilon, "--risk-epsilon")
    options.report_times = _number_list(report_times, "--report-times")
    try:
        options.windows = [(_number(a, "--windows"), _number(b, "--windows")) for a, b in (windows or [])]
    except (TypeError, ValueError):
        raise Error("error: --windows: expected (a, b) pairs of numbers") from None
    options.parameters = _parameters(parameters)
    options.cache_dir = "" if cache_dir is None else _path(cache_dir, "--cache-dir")
    options.compiler = "" if compiler is None else _path(compiler, "--compiler")
    stream = _progress_stream(progress)
    if stream is None:
        return Simulation(model._native.simulate(options), model)
    return Simulation(_simulate_showing_progress(model._native, options, stream), model)


def _progress_stream(progress):
    """Where simulate's progress line goes: nowhere (False), sys.stderr (True) or a text stream."""
    if progress is None or progress is False:
        return None
    if progress is True:
        return _sys.stderr
    if callable(getattr(progress, "write", None)):
        return progress
    raise Error(f"error: progress: expected True, False or a text stream, got {_shown(progress)}")


def _simulate_showing_progress(native_model, options, stream):
    """The native simulate, with its progress line written to `stream` as the command draws it on
    a terminal. pfgen's threads only append the text (without the GIL); a Python thread of ours
    writes it out five times a second, and what is left once the simulation returns."""
    text = _pfgen.ProgressText()
    options.report_progress_to(text)
    done = _threading.Event()

    def show():
        while True:
            finished = done.wait(0.2)
            part = text.take()
            if part:
                stream.write(part)
                stream.flush()
            if finished:
                return

    shower = _threading.Thread(target=show, name="pfgen simulate progress", daemon=True)
    shower.start()
    try:
        return native_model.simulate(options)
    finally:
        done.set()
        shower.join()


def _flag(value, option):
    """A switch (--profile, --full-covariance): True or False (None: False)."""
    if value is None:
        return False
    if not isinstance(value, (bool, _np.bool_)):
        raise Error(f"error: {option}: expected True or False, got {_shown(value)}")
    return bool(value)


def _data_column(values, name, rows):
    """One column of in-memory data as floats (None, pandas' NA and NaN: missing)."""
    to_numpy = getattr(values, "to_numpy", None)
    try:
        if to_numpy is not None:  # a pandas Series: its NA as NaN
            array = to_numpy(dtype=float, na_value=_np.nan)
        else:
            array = _np.asarray(values, dtype=float)
    except OverflowError:
        raise _out_of_range(f"--data column {name!r}", values) from None
    except (TypeError, ValueError):
        raise Error(f"error: --data: column {name!r}: expected numbers (None or NaN where missing)") from None
    if array.ndim != 1:
        raise Error(f"error: --data: column {name!r}: expected a vector of numbers, got an array of shape {array.shape}")
    if rows is not None and len(array) != rows:
        raise Error(f"error: --data: column {name!r} has {len(array)} values, the first column {rows}")
    return array


def _set_record(options, data, time):
    """The record of estimate and fit: a CSV file's path, or in memory a dict of columns, a pandas
    DataFrame (its index too when it is named as `time` and no column is), or a pair (times,
    values) whose columns are named y1..yp."""
    if isinstance(data, (str, bytes, _os.PathLike)):
        options.data_path = _path(data, "--data")
        return
    if isinstance(data, tuple) and len(data) == 2:
        times, values = data
        times = _data_column(times, time, None)
        try:
            values = _float_array(values, "--data")
        except (TypeError, ValueError):
            raise Error("error: --data: the values: expected an array of numbers (NaN where missing)") from None
        if values.ndim == 1:
            values = values.reshape(-1, 1)
        if values.ndim != 2 or values.shape[0] != len(times):
            raise Error(f"error: --data: {len(times)} times need values of shape ({len(times)}, p), "
                        f"got {values.shape}")
        columns = [time] + [f"y{i + 1}" for i in range(values.shape[1])]
        options.set_data(columns, _np.column_stack([times, values]) if values.size else times.reshape(-1, 1))
        return
    items = getattr(data, "items", None)
    if items is None:
        raise Error("error: --data: expected a CSV file's path, a dict of columns, a pandas DataFrame or a pair "
                    f"(times, values), got {type(data).__name__}")
    columns = list(data.keys())
    index = getattr(data, "index", None)
    named_index = getattr(index, "name", None)
    cells = []
    if named_index is not None and named_index == time and time not in columns:
        columns = [time] + columns
        cells.append(_data_column(index, time, None))
    for name in list(data.keys()):
        if not isinstance(name, str):
            raise Error(f"error: --data: a column's name must be a str, got {_shown(name)}")
        cells.append(_data_column(data[name], name, len(cells[0]) if cells else None))
    rows = len(cells[0]) if cells else 0
    options.set_data(columns, _np.column_stack(cells) if cells else _np.zeros((rows, 0)))


def _record_options(options, data, time, columns, data_form, substeps, t0, parameters, cache_dir, compiler):
    """estimate's and fit's shared settings (their options of the same names)."""
    time = _text(time, "--time-column", "t")
    _set_record(options, data, time)
    options.time_column = time
    options.columns = _names(columns, "--columns", "a column's name")
    options.data_form = _text(data_form, "--data-form", "increments")
    options.substeps = _whole(1 if substeps is None else substeps, "--substeps")
    options.t0 = _optional_number(t0, "--t0")
    options.parameters = _parameters(parameters)
    options.cache_dir = "" if cache_dir is None else _path(cache_dir, "--cache-dir")
    options.compiler = "" if compiler is None else _path(compiler, "--compiler")


def _check_model(model, call):
    if not isinstance(model, Model):
        raise TypeError(f"pfgen.{call}: expected a pfgen.Model (pfgen.Model.load(path)), got {type(model).__name__}")


class FilterRun:
    """One filter over a record, per data row: m and sd (N x n), P (N x n x n, with
    full_covariance=True, else None), predicted, innovation and normalized (N x p)."""

    def __init__(self, name, series, states, observed, full_covariance):
        self.name = name
        rows = len(series[next(iter(series))])

        def stacked(kind, names):
            return _np.column_stack([series[f"{name}_{kind}_{x}"] for x in names]) if names else _np.zeros((rows, 0))

        self.m = stacked("m", states)
        self.sd = stacked("sd", states)
        self.P = None
        if full_covariance:
            n = len(states)
            self.P = _np.empty((rows, n, n))
            for i in range(n):
                for j in range(i, n):
                    self.P[:, i, j] = self.P[:, j, i] = series[f"{name}_P_{states[i]}_{states[j]}"]
        self.predicted = stacked("predicted", observed)
        self.innovation = stacked("innovation", observed)
        self.normalized = stacked("normalized", observed)

    def __repr__(self):
        return f"<pfgen.FilterRun {self.name}: {len(self.m)} rows>"


class Estimate:
    """What ``pfgen estimate`` computes: the report (its table), the scores per filter, the CSV
    ``-o`` writes and its columns as numpy arrays, and per filter a FilterRun of arrays."""

    def __init__(self, native, model, full_covariance):
        self.report = native.report  #: the command's standard output, before the paths of files
        self.csv = native.csv        #: the CSV ``-o`` writes
        self.time_column = native.time_column
        self.observation_columns = list(native.observation_columns)
        self.state_names = model.state_names
        #: column name -> numpy array, a value per data row (NaN where the CSV is empty)
        self.series = dict(zip(native.columns, native.series))
        #: filter name -> dict of the scores: log_likelihood, increment_log_density (continuous data;
        #: else NaN), count, mean_square, band (low, high), consistent, white, ljung_box (per
        #: observation entry: lags, statistic, p_value), verdict, and stopped: where and why the
        #: filter stopped before the record's end (its scores then those of the rows up to that one; its
        #: series NaN from there), or None when it ran through
        self.scores = {}
        for f in native.filters:
            self.scores[f.name] = {
                "log_likelihood": f.log_likelihood, "increment_log_density": f.increment_log_density,
                "count": f.count, "mean_square": f.mean_square, "band": (f.band_low, f.band_high),
                "consistent": f.consistent, "white": f.white,
                "ljung_box": [{"lags": lags, "statistic": q, "p_value": p}
                              for lags, q, p in zip(f.ljung_box_lags, f.ljung_box_statistic, f.ljung_box_p)],
                "verdict": f.verdict, "stopped": f.stopped or None}
        #: filter name -> FilterRun
        self.filters = {name: FilterRun(name, self.series, self.state_names, self.observation_columns, full_covariance)
                        for name in self.scores}

    @property
    def t(self):
        """The data's times."""
        return self.series[self.time_column]

    @property
    def data(self):
        """The observations as read (N x p; NaN where missing)."""
        return _np.column_stack([self.series[y] for y in self.observation_columns])

    def __repr__(self):
        return self.report


def estimate(model, data, filters=None, *, time=None, columns=None, data_form=None, substeps=None, t0=None,
             parameters=None, full_covariance=False, cache_dir=None, compiler=None):
    """``pfgen estimate``: the model's filters (or ``filters``) over a record. ``data``: a CSV
    file's path (--data), or in memory a dict of columns, a pandas DataFrame or a pair (times,
    values) with NaN where an observation is missing. ``time`` is --time-column, ``columns``
    --columns, ``parameters={"mu": 0.5}`` --set mu=0.5; the others are the options of the same
    names. The GIL is released while it runs."""
    _check_model(model, "estimate")
    options = _pfgen.EstimateOptions()
    record = options.record
    _record_options(record, data, time, columns, data_form, substeps, t0, parameters, cache_dir, compiler)
    options.record = record
    options.filters = _names(filters, "--filters")
    options.full_covariance = _flag(full_covariance, "--full-covariance")
    options.series = True
    return Estimate(model._native.estimate(options), model, options.full_covariance)


class Fit:
    """What ``pfgen fit`` computes: the report (its table), the JSON ``-o`` writes, and the
    estimates with their standard errors and intervals."""

    def __init__(self, native):
        self.report = native.report        #: the command's standard output, before the path of its file
        self.json = native.json            #: the JSON ``-o FILE.json`` writes
        self.converged = native.converged  #: False: the optimiser stopped otherwise (stop_reason), no estimates
        self.stop_reason = native.stop_reason
        self.log_likelihood = native.log_likelihood
        self.aic = native.aic
        self.evaluations = native.evaluations
        parameters = native.parameters
        #: name -> estimate (without convergence: the last point)
        self.estimates = {p.name: p.estimate for p in parameters}
        #: name -> standard error (NaN where the observed information is not positive definite, or
        #: where the estimate is at the edge of where the filter runs: see note)
        self.std_errors = {p.name: p.std_error for p in parameters}
        #: name -> (low, high), the 95 % Wald interval
        self.wald = {p.name: (p.wald_low, p.wald_high) for p in parameters}
        #: name -> (low, high), the 95 % profile-likelihood interval (NaN unless profile=True)
        self.profile = {p.name: (p.profile_low, p.profile_high) for p in parameters}
        #: the estimated parameters at a bound
        self.at_bound = [p.name for p in parameters if p.at_bound]
        #: name -> (low, high): whether that end of the profile interval is the last value where the
        #: filter runs (a moment filter's likelihood ends where its moments leave the realisable set)
        self.profile_fails_beyond = {p.name: (p.profile_low_fails_beyond, p.profile_high_fails_beyond)
                                     for p in parameters}
        #: True where the estimate is at the edge of where the filter runs: not a maximum, no standard errors
        self.at_edge = native.at_edge
        #: why there are no standard errors, if there are none ("" otherwise)
        self.note = native.note

    def __repr__(self):
        return self.report


def _bounds(bounds):
    """--bounds as a dict name -> (low, high), an open end None (or an infinity)."""
    if bounds is None:
        return []
    try:
        items = list(bounds.items())
    except (AttributeError, TypeError):
        raise Error(f"error: --bounds: expected a dict of parameter names and (low, high) pairs, "
                    f"got {type(bounds).__name__}") from None
    out = []
    for name, pair in items:
        if not isinstance(name, str):
            raise Error(f"error: --bounds: a parameter's name must be a str, got {_shown(name)}")
        try:
            low, high = pair
        except (TypeError, ValueError):
            raise Error(f"error: --bounds {name}: expected a pair (low, high), None for an open end, "
                        f"got {_shown(pair)}") from None
        low = -_np.inf if low is None else _number(low, f"--bounds {name}")
        high = _np.inf if high is None else _number(high, f"--bounds {name}")
        out.append(_pfgen.Bound(name, low, high))
    return out


def fit(model, data, estimate, *, bounds=None, filter=None, starts=None, seed=None, profile=False, time=None,
        columns=None, data_form=None, substeps=None, t0=None, parameters=None, cache_dir=None, compiler=None):
    """``pfgen fit``: the parameters named in ``estimate`` at the maximum of one filter's
    log-likelihood over a record (``filter``: default the model's first). ``bounds``: a dict
    name -> (low, high), None for an open end. ``data`` and the record's settings as estimate's.
    A fit that does not converge is returned with converged False, as the command prints it."""
    _check_model(model, "fit")
    options = _pfgen.FitOptions()
    record = options.record
    _record_options(record, data, time, columns, data_form, substeps, t0, parameters, cache_dir, compiler)
    options.record = record
    options.estimate = _names(estimate, "--estimate", "a parameter's name")
    options.bounds = _bounds(bounds)
    options.filter = _text(filter, "--filter", "")
    options.starts = _whole(1 if starts is None else starts, "--starts")
    options.seed = _whole(1 if seed is None else seed, "--seed")
    options.profile = _flag(profile, "--profile")
    return Fit(model._native.fit(options))
