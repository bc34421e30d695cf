"""Identification: recorded data in, model parameters with uncertainties out."""

from .paramfile import load_params, params_to_yaml, save_params, write_atomic

__all__ = ["load_params", "params_to_yaml", "save_params", "write_atomic"]
