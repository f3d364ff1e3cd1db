"""Transform models and robust estimation."""
from .models import LinearModel, PolynomialModel, ThinPlateSplineModel, fit_model, model_from_dict
from .ransac import ransac

__all__ = ["LinearModel", "PolynomialModel", "ThinPlateSplineModel", "fit_model", "model_from_dict", "ransac"]
