"""Transform models and robust estimation."""
from .models import (MODEL_CHOICES, LinearModel, PolynomialModel, ThinPlateSplineModel, canonical_model,
                     fit_model, model_from_dict)
from .ransac import ransac

__all__ = ["MODEL_CHOICES", "LinearModel", "PolynomialModel", "ThinPlateSplineModel", "canonical_model",
           "fit_model", "model_from_dict", "ransac"]
