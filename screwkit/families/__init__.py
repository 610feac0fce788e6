"""Parametric mechanism families with closed-form kinematics."""
