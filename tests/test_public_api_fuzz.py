"""Bad input never escapes as a raw error: every public function answers or raises
``vines.ParameterError`` (one line naming the argument) for junk types, non-finite values,
out-of-range numbers and in-range extremes (issue 30 item 4).

Derandomized hypothesis: the same examples on every run. Each example replaces one or two
keyword arguments of a cheap valid call (``_public_api_cases``) by a drawn value; valid
values of arguments that set the cost of a call are drawn from bounded lists.
"""
import inspect

import numpy as np
import pytest
from _public_api_cases import EXTREMES, JUNK, SMALL, cases
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vines
from vines import ParameterError

CASES = cases()
N_EXAMPLES = 40


def _arguments(fn, base) -> list[str]:
    """Every keyword the function takes (the valid call's first)."""
    sig = inspect.signature(fn)
    names = [n for n, p in sig.parameters.items() if p.kind != inspect.Parameter.VAR_KEYWORD]
    return list(dict.fromkeys(list(base) + names))


def _values(arg: str, bounded) -> st.SearchStrategy:
    if isinstance(bounded, dict) and arg in bounded:
        valid = bounded[arg]
    else:
        valid = SMALL if arg in bounded else EXTREMES
    return st.sampled_from(JUNK + tuple(valid))


def _check_call(fn, kwargs) -> None:
    try:
        fn(**kwargs)
    except ParameterError as err:
        message = str(err)
        assert isinstance(err.name, str) and err.name, message
        assert message.startswith(f"invalid {err.name} = ") and "\n" not in message, message


@pytest.mark.parametrize("name", sorted(CASES))
def test_junk_and_extremes_give_a_result_or_a_parameter_error(name):
    fn, base, bounded = CASES[name]
    fn(**base)                                   # the valid call itself works (and compiles)
    args = _arguments(fn, base)

    @settings(derandomize=True, max_examples=N_EXAMPLES, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(st.data())
    def fuzz(data):
        chosen = data.draw(st.lists(st.sampled_from(args), min_size=1, max_size=2, unique=True))
        kwargs = dict(base)
        for arg in chosen:
            kwargs[arg] = data.draw(_values(arg, bounded), label=arg)
        _check_call(fn, kwargs)

    fuzz()


#: cases whose every pass takes over ~10 s (design: arguments it ignores, such as n_eta
#: beside a given eta, accept any value and each such call runs the whole design)
SLOW_PASS = {"design"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_PASS
                                  else n for n in sorted(CASES)])
def test_every_junk_value_alone_in_every_argument(name):
    """Each junk value in each argument, one at a time, the others valid. The drawn examples
    above visit a few of these pairs only (40 of ~400 for a case, one or two arguments
    replaced): ``continue_branch(param=None)`` escaped as a KeyError because no draw
    happened to put None in ``param``; this pass visits every pair (~10 s in all)."""
    fn, base, _bounded = CASES[name]
    for arg in _arguments(fn, base):
        for value in JUNK:
            _check_call(fn, {**base, arg: value})


@pytest.mark.parametrize("call, name", [
    (lambda: vines.simulate_batch(eta="", omega=1.0, F=0.05), "eta"),
    (lambda: vines.simulate_batch(eta=[0.1, 0.2], omega=[1.0, 1.1, 1.2], F=0.05), "omega"),
    (lambda: CASES["stability_map"][0](eta=[0.1], omega={}, F=0.05), "omega"),
    (lambda: CASES["bifurcation_sweep"][0](param=np.array([1.0, np.nan]), values=[0.1]),
     "param"),
    (lambda: CASES["bifurcation_sweep"][0]("F", [0.05, np.nan], eta=0.05, omega=1.0), "values"),
    (lambda: CASES["bifurcation_sweep"][0]("F", [0.05], eta=0.05, omega=1e-300), "n_record"),
    (lambda: CASES["find_1to1"][0](0.05, 1.0, 0.05, seeds=[1.0]), "seeds"),
    (lambda: CASES["find_1to1"][0](0.05, 1.0, 0.05, simulation=np.array([1.0])),
     "simulation"),
    (lambda: CASES["find_sequence"][0]({"eta": 0.1}, "LR"), "params"),
    (lambda: CASES["continue_branch"][0]("F", 0.1, 0.09, fixed=0.5), "fixed"),
    (lambda: CASES["continue_branch"][0](param=None, start=0.0, stop=0.0), "param"),
    (lambda: CASES["continue_branch"][0]("F", 0.1, 0.09, fixed={"eta": 0.2, "omega": 1.0},
                                         orbit="abc"), "orbit"),
    (lambda: CASES["robust_point"][0](0.05, 1.0, 0.05, threshold="x"), "threshold"),
    (lambda: CASES["census"][0](0.05, 1.0, 0.05, states=""), "states"),
    (lambda: CASES["basin_slice"][0](0.05, 1.0, 0.05, z_m0={}, v_m0=[0.0]), "z_m0"),
    (lambda: CASES["boundaries"][0](0.05, (0.05, 0.1), (0.9, 1.1), r=""), "r"),
    (lambda: CASES["boundaries"][0](0.05, (0.05, 0.1), (0.9, 1.1), class_map=1.0),
     "class_map"),
    (lambda: CASES["optimal_tmd"][0](mu="", d=0.01, band=(0.8, 1.2)), "mu"),
    (lambda: CASES["work_precision"][0](0.05, 1.0, 0.05, t_end=2.0, t_transient=1.0, d=0.0),
     "omega"),
    (lambda: CASES["work_precision"][0](0.05, 1.0, 0.05, t_end=2.0, t_transient=1.0,
                                        rk_methods="RK45"), "rk_methods"),
    (lambda: CASES["window_convergence"][0]([{"eta": 0.1, "omega": 1.0}]), "points[0]"),
    (lambda: CASES["grid_convergence"][0](resolutions=(11, 20)), "resolutions"),
    (lambda: CASES["vstick_convergence"][0]([{"eta": 0.1, "omega": 1.0, "F": 0.1}],
                                            v_sticks=[np.nan]), "v_sticks"),
])
def test_reported_cases_name_the_argument(call, name):
    """The calls of issue 30 (and one per function fixed since) name the bad argument."""
    with pytest.raises(ParameterError) as err:
        call()
    assert err.value.name == name, str(err.value)
