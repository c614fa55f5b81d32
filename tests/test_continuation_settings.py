"""One ``ContinuationSettings`` for the 1:1 continuation and any wall sequence: the same
validation and the same meaning of ``max_points`` for both."""
import pytest

from vines import ParameterError
from vines.core.params import MAX_POINTS_DEFAULT, ModelParams
from vines.orbits.continuation import sequence as seq
from vines.orbits.continuation.branch import Branch
from vines.orbits.continuation.one_to_one import continue_branch
from vines.orbits.continuation.settings import ContinuationSettings

P = ModelParams(eta=0.2, omega=1.0, F=0.1)


def _one_to_one(**kw):
    return continue_branch("F", 0.1, 0.09, fixed={"eta": 0.2, "omega": 1.0}, **kw)


def _sequence(**kw):
    return seq.continue_sequence(P, "LR", 1, "F", 0.09, settings=ContinuationSettings(**kw))


FAMILIES = pytest.mark.parametrize("run", [_one_to_one, _sequence], ids=["1:1", "LR/1"])


def test_old_name_is_the_one_class():
    assert seq.ContinueSettings is ContinuationSettings


@FAMILIES
def test_a_step_needing_more_than_max_points_is_refused(run):
    # |0.09 - 0.1| / 0.001 = 10 points > 5
    with pytest.raises(ParameterError) as err:
        run(step=0.001, max_points=5)
    assert err.value.name == "step" and "max_points = 5" in str(err.value)


@FAMILIES
@pytest.mark.parametrize("kw, name", [(dict(max_points=0), "max_points"),
                                      (dict(max_inadmissible=0), "max_inadmissible"),
                                      (dict(step=0.0), "step"), (dict(switch="yes"), "switch"),
                                      (dict(min_step=0.0), "min_step")])
def test_same_validation(run, kw, name):
    with pytest.raises(ParameterError) as err:
        run(**kw)
    assert err.value.name == name


def test_defaults_per_continuation():
    fixed = {"eta": 0.2, "omega": 1.0}
    one = ContinuationSettings(param="F", start=0.1, stop=0.09, fixed=fixed)
    assert one.max_points == MAX_POINTS_DEFAULT and one.step_size == pytest.approx(1e-4)
    bound = ContinuationSettings().bound("F", 0.1, 0.09, fixed, seq.MAX_BRANCH_POINTS_DEFAULT)
    assert bound.max_points == seq.MAX_BRANCH_POINTS_DEFAULT == 2000
    assert ContinuationSettings(max_points=7).bound("F", 0.1, 0.09, fixed, 2000).max_points == 7


def test_sequence_refuses_bound_settings():
    with pytest.raises(ParameterError) as err:
        seq.continue_sequence(P, "LR", 1, "F", 0.09, settings=ContinuationSettings(
            param="F", start=0.1, stop=0.09, fixed={"eta": 0.2, "omega": 1.0}))
    assert err.value.name == "settings"


@FAMILIES
def test_max_points_caps_an_arclength_branch_of_either_family(run):
    """The default step (|stop - start|/100) is not refused; the branch stops at 3 points,
    and both results are the one branch type (``Branch``)."""
    br = run(max_points=3)
    assert type(br) is Branch and br.param == "F" and br.born_at is None
    assert len(br) == len(br.points) == 3 and "max_points" in br.stopped
