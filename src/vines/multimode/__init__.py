"""A linear host of several degrees of freedom carrying several absorbers (VI NES, TMD, TMD
with end stops), simulated exactly event by event (docs/model.md, "General model").

``model`` (Host, Absorber, HarmonicBase, HostModel: validated where built), ``modelfile``
(the YAML model file), ``system`` (the linear system of each set of stuck absorbers, in
closed form), ``kernel`` (the compiled engine), ``simulate`` (``simulate_model``, settings
and result). ``import vines.multimode`` loads no numba: the engine is loaded by
``simulate_model``.
"""
from .model import Absorber, HarmonicBase, Host, HostModel
from .modelfile import model_from_dict, read_model
from .simulate import ModelResult, ModelSettings, simulate_model

__all__ = ["Absorber", "HarmonicBase", "Host", "HostModel", "ModelResult", "ModelSettings",
           "model_from_dict", "read_model", "simulate_model"]
