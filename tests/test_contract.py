"""The contract every registered model keeps (issue 10): one shape of answer, one way to
reject a misspelt option, strict JSON, a short repr.

Parametrized over :data:`webfem.models.registry.MODELS`, so a model added to the registry is
held to it without a new test.
"""

import json
import math
import pickle

import pytest

import webfem
from webfem.errors import InputError
from webfem.models.registry import MODELS
from webfem.result import SUMMARY_KEYS

from conftest import FLYING

#: The base case at 40 m/s, where the web flies (fluid film everywhere): every model answers
#: in about a second.
CASE = FLYING
NAMES = sorted(MODELS)
pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


@pytest.fixture(scope="module", params=NAMES)
def answer(request):
    return request.param, webfem.solve(CASE, model=request.param)


def test_every_summary_key_present_and_finite(answer):
    model, result = answer
    data = result.to_dict()
    assert list(data)[:len(SUMMARY_KEYS)] == list(SUMMARY_KEYS)
    assert data["model"] == model and data["converged"] is True
    for key in SUMMARY_KEYS:
        value = result[key]
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            assert math.isfinite(value), (model, key, value)
            assert data[key] == value, (model, key)
    assert data["regime"] in ("boundary", "mixed", "fluid")
    assert 0.0 < data["h_min"] <= data["h_center"]
    assert 0.0 <= data["mu"] <= CASE.friction.mu_cc


@pytest.mark.parametrize("model", NAMES)
@pytest.mark.parametrize("how", ["keyword", "mapping"])
def test_misspelt_option_is_rejected(model, how):
    """``levle=2`` names 'levle' and, where the model has a level, suggests 'level'."""
    with pytest.raises(InputError) as err:
        if how == "keyword":
            webfem.solve(CASE, model=model, levle=2)
        else:
            webfem.solve(CASE, model=model, options={"levle": 2})
    message = str(err.value)
    assert "'levle'" in message and "\n" not in message
    if "level" in MODELS[model].options.names():
        assert "did you mean 'level'" in message
    else:
        assert "did you mean" not in message


def test_json_round_trip(answer):
    model, result = answer
    text = result.summary.to_json()
    assert json.loads(text) == result.to_dict()
    assert "NaN" not in text and "Infinity" not in text


def test_short_repr(answer):
    model, result = answer
    text = repr(result)
    assert len(text) < 1000 and model in text
    assert len(repr(result.summary)) < 1000 and len(repr(result.fields)) < 1000


def test_slim_result_pickles(answer):
    """Worker processes send slim results back: they must pickle and keep the summary."""
    _, result = answer
    back = pickle.loads(pickle.dumps(result.slim()))
    assert back.to_dict() == result.to_dict()
