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
"""
import json as _json
import re as _re

import numpy as _np

from . import _pfgen

__all__ = ["Error", "Model", "Filter", "Simulation", "simulate", "__version__"]
__version__ = _pfgen.version()

#: The one exception pfgen raises for a bad model, option, point or file. Its message is the line
#: the command prints after "pfgen: " ("m.yaml:4:15: error: ..." or "error: ...").
Error = _pfgen.Error


def _number_list(values, option):
    """A number or a sequence of numbers (or a numpy array) as a list of floats."""
    if values is None:
        return []
    try:
        array = _np.asarray(values, dtype=float)
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
        array = _np.asarray(values, dtype=float)
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
    except (TypeError, ValueError):
        raise Error(f"error: {option}: {value!r} is not a number") from None


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


def _names(names, option):
    """Filter names: a list, or one name as a string."""
    if names is None:
        return []
    if isinstance(names, str):
        return [names]
    names = list(names)
    for name in names:
        if not isinstance(name, str):
            raise Error(f"error: {option}: {name!r} is not a filter's name")
    return names


def _arrays(value):
    """eval's JSON with its lists as numpy arrays (its objects stay dicts)."""
    if isinstance(value, dict):
        return {key: _arrays(item) for key, item in value.items()}
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

    def eval(self, t, m, P, /, *, m_delayed=None, x_star=None, x_star_delayed=None, phi=None, parameters=None,
             **more_parameters):
        """The filter's values at (t, m, P), with parameters given new values by keyword (or in
        ``parameters``, for one named like an argument of eval, such as phi):
        ``pfgen eval --t T --m M --P P --set name=value``. Returns the command's JSON without
        model and filter, each list a numpy array: m_drift, gain, P_drift (a sampled filter's
        under "prediction" and "update", a delayed filter's inputs under "delayed_inputs")."""
        values = dict(parameters or {})
        values.update(more_parameters)
        native = self._native.eval(
            _number(t, "--t"), _number_list(m, "--m"), _number_matrix(P, "--P"),
            {str(name): _number(value, f"--set {name}") for name, value in values.items()},
            _number_list(m_delayed, "--m-delayed"), _number_list(x_star, "--x-star"),
            _number_list(x_star_delayed, "--x-star-delayed"), _number_list(phi, "--phi"))
        values = _json.loads(native.json)
        return {key: _arrays(value) for key, value in values.items() if key not in ("model", "filter")}

    def to_sympy(self):
        """The equations as SymPy matrices, equal to the printed ones:

            dm = m_drift dt + gain (dy - predicted_observation dt),   dP = P_drift dt

        (a sampled filter's m_drift and P_drift are its prediction between samples, and its gain
        is empty; a polynomial observation's dP adds sum_r P_gain[r] (dy_r - predicted_observation_r dt)). Returns a SympyFilter with m_drift (n x 1), gain (n x p), P_drift (n x n),
        predicted_observation (p x 1), definitions (name -> expression, in order) and symbols
        (name -> Symbol: m1, P11, ..., the parameters, the time)."""
        try:
            import sympy
        except ImportError as e:  # pragma: no cover - the set-up installs python3-sympy
            raise ImportError("Filter.to_sympy needs SymPy (Debian: apt-get install python3-sympy)") from e
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
            P_gain=[sympy.Matrix(n, n, [parse(x) for row in L for x in row]) for L in e.P_gain])


class SympyFilter:
    """Filter.to_sympy's result."""

    def __init__(self, m_drift, gain, P_drift, predicted_observation, definitions, symbols, P_gain):
        self.m_drift, self.gain, self.P_drift = m_drift, gain, P_drift
        self.predicted_observation, self.definitions, self.symbols = predicted_observation, definitions, symbols
        #: a polynomial observation's dP = P_drift dt + sum_r P_gain[r] (dy_r - predicted_observation_r dt);
        #: empty for the other observations
        self.P_gain = P_gain

    def __repr__(self):
        return f"SympyFilter(m_drift={self.m_drift}, gain={self.gain}, P_drift={self.P_drift})"


class Model:
    """A checked model: from a model file (load), YAML text (from_yaml)."""

    def __init__(self, native):
        self._native = native

    @staticmethod
    def load(path):
        """Reads and checks a model file (as every command does)."""
        return Model(_pfgen.Model.load(str(path)))

    @staticmethod
    def from_yaml(text, source="<yaml>"):
        """Reads a model from YAML text; ``source`` names it in messages."""
        return Model(_pfgen.Model.from_yaml(text, source))

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
        return Filter(self, self._native.derive("" if kind is None else str(kind)))

    def latex_document(self, kinds=None):
        """``pfgen latex``: a LaTeX document with these filters (default: the default ones)."""
        return self._native.latex_document(_names(kinds, "--filter"))

    def codegen(self, directory=None, kinds=None, scalar=None, language="cpp", namespace="pfgen_models",
                eigen=False, dt=None):
        """``pfgen codegen``: the filters' code in C++ or C (language "cpp" or "c"), with scalar
        "template" (C++), "float" or "double" (default: C++ template, C double). With a directory,
        the files are written there (all or none) and their paths returned; without, a dict from
        each file's relative path to its text."""
        options = _pfgen.CodegenOptions()
        options.filters = _names(kinds, "--filter")
        options.language = str(language)
        options.scalar = str(scalar or "")
        options.name_space = str(namespace)
        options.eigen = bool(eigen)
        options.dt = _optional_number(dt, "--dt")
        if directory is None:
            return {f.path: f.contents for f in self._native.codegen_files(options)}
        return self._native.codegen_to(str(directory), options)

    def simulate(self, **settings):
        """pfgen.simulate(self, ...)."""
        return simulate(self, **settings)


class Simulation:
    """What ``pfgen simulate`` computes: the report (its table), the time series of its CSV as
    numpy arrays, and a summary per filter (and the particle reference)."""

    def __init__(self, native):
        self.report = native.report    #: the command's standard output, before the paths of files
        self.notes = native.notes      #: what it says on stderr ("pfgen: note: ...")
        self.csv = native.csv          #: the CSV ``-o`` writes
        self.runs = native.runs
        self.steps = native.steps
        #: column name -> numpy array, one value per recorded time (NaN where the CSV is empty)
        self.series = {name: _np.array(values, dtype=float) for name, values in zip(native.columns, native.series)}
        #: filter name -> dict of completed, diverged, psd_losses, rms, rms_se, peak_median,
        #: peak_q95, reference_distance, reference_distance_se (per state: numpy arrays)
        self.summary = {}
        for f in native.filters:
            self.summary[f.name] = {
                "completed": f.completed, "diverged": f.diverged, "psd_losses": f.psd_losses,
                "rms": _np.array(f.rms), "rms_se": _np.array(f.rms_se),
                "peak_median": _np.array(f.peak_median), "peak_q95": _np.array(f.peak_q95),
                "reference_distance": _np.array(f.reference_distance),
                "reference_distance_se": _np.array(f.reference_distance_se)}

    @property
    def t(self):
        return self.series["t"]

    def __repr__(self):
        return self.report


def simulate(model, runs=None, T=None, dt=None, filters=None, seed=None, threads=0, reference=None, *,
             scheme=None, x0=None, record_points=None, shown_run=None, bound=None, risk_epsilon=None,
             report_times=None, windows=None, parameters=None, cache_dir=None, compiler=None, batch=8):
    """``pfgen simulate``: the model's filters (or ``filters``) against simulated truths in Monte
    Carlo, with the particle reference of ``reference`` particles. Unset settings come from the
    model's simulation: section, then pfgen's defaults. The GIL is released while it runs."""
    options = _pfgen.SimulationOptions()
    options.runs = _whole(runs, "--runs")
    options.T = _optional_number(T, "--T")
    options.dt = _optional_number(dt, "--dt")
    options.filters = _names(filters, "--filters")
    options.seed = _whole(seed, "--seed")
    options.threads = _whole(threads, "--threads", 2**32 - 1)
    options.batch = _whole(batch, "--batch", 2**64 - 1)
    options.reference = _whole(reference, "--reference")
    options.scheme = None if scheme is None else str(scheme)
    options.x0 = None if x0 is None else str(x0)
    options.record_points = _whole(record_points, "--record-points")
    options.shown_run = _whole(shown_run, "--shown-run")
    options.bound = _optional_number(bound, "--bound")
    options.risk_epsilon = _optional_number(risk_epsilon, "--risk-epsilon")
    options.report_times = _number_list(report_times, "--report-times")
    try:
        options.windows = [(_number(a, "--windows"), _number(b, "--windows")) for a, b in (windows or [])]
    except (TypeError, ValueError):
        raise Error("error: --windows: expected (a, b) pairs of numbers") from None
    options.parameters = {str(name): _number(value, f"--set {name}") for name, value in (parameters or {}).items()}
    options.cache_dir = str(cache_dir or "")
    options.compiler = str(compiler or "")
    return Simulation(model._native.simulate(options))
