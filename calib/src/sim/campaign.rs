//! Whole-campaign simulator: perturbed robot, flange camera, joints, images, truth.
