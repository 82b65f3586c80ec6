"""The thesis's numbers, in SI units, each with the section of the thesis it comes from.

This module is the one home of the thesis's parameters: every default elsewhere in the library
refers to a name here. Where the thesis gives no number, the comment says where the value comes
from. The source is the PhD thesis in the project's shared folder, chapters 6 and 7.
"""

from __future__ import annotations

import math

# --- Pad and module geometry -----------------------------------------------------------------
#: Side of one square module and the pitch of the grid, m (Section 6.1.2: 45 x 45 mm air channel).
MODULE_PITCH_M = 0.045
#: Rows and columns of the prototype pad (Section 6.1.2, Fig. 6.4a: 2 x 3).
PROTOTYPE_ROWS = 2
PROTOTYPE_COLS = 3
#: Channels of the Pneumaticbox (Section 6.1.1: 8 channels).
BOX_CHANNELS = 8
#: Side of one module's air chamber, m (Section 6.1.1: "a 45x45 mm piece of acetate" defines
#: the channel of each square).
CHAMBER_SIDE_M = 0.045
#: Thickness of the upper silicone layer, m (Section 6.1: 1.5 mm of EcoFlex 00-30).
LAYER_THICKNESS_M = 0.0015
#: Bonded width between neighbouring chambers, m: the module pitch less the chamber side. The
#: seed gives a 45 mm chamber (Section 6.1.1) and 45 mm modules (Section 6.1.2, the grid of
#: Fig. 6.4a), so within its figures the chambers meet at their clamped edges (0 mm); the
#: thickness of the mould's grid walls (Fig. 6.2a) is not given.
SEAM_WIDTH_M = MODULE_PITCH_M - CHAMBER_SIDE_M
#: Air left under a flat (uninflated) layer, in the acetate channel and the tube inlet, m^3.
#: Not in the thesis; 0.2 mL (a 45 x 45 mm sheet leaves a gap of about 0.1 mm). Shared by the
#: FEM's chamber and the simulator.
CHAMBER_GAP_VOLUME_M3 = 0.2e-6
#: Dead volume of one channel's tubing, m^3. The thesis names the tube (Section 6.1.1: SPX-60 FB
#: Versilon silicone tubing) but not its bore or length; 1 m of 2 mm bore (3.14 mL). Shared by
#: the FEM's sealed chamber and the simulator's pneumatics.
TUBING_VOLUME_M3 = math.pi * 1.0e-3**2 * 1.0

# --- Inflation (Section 6.2.1.1) -------------------------------------------------------------
#: p0, the initial inflating pressure of every module, Pa (1.1 kPa: a module about 9 mm high).
P0_PA = 1100.0
#: Usable range of p0, Pa (Section 6.2.1.1: 0.5 to 2.8 kPa).
P0_RANGE_PA = (500.0, 2800.0)
#: t_adj, tolerance of the initial adjustment, Pa (0.03 kPa).
ADJUST_TOLERANCE_PA = 30.0
#: Reads averaged into the reference after the adjustment (Section 6.2.1.1: 10 reads).
REFERENCE_READS = 10
#: Largest pressure the software lets a module reach, Pa (Section 7.2: the FEM studies and the
#: module's rated range end at 3 kPa).
MAX_PRESSURE_PA = 3000.0

# --- Sensing (Sections 6.2.1.2, 6.2.2, 6.3) --------------------------------------------------
#: Ambient (atmospheric) pressure added to the box's gauge readings where a message needs an
#: absolute pressure (``sensor_msgs/FluidPressure``), Pa. Not in the thesis: the ISO 2533 standard
#: atmosphere at sea level; an installation sets its own (``box.ambient_pressure_kpa``).
AMBIENT_PRESSURE_PA = 101325.0
#: White noise of one pressure sample, Pa rms. Not in the thesis (it says only that the data "look
#: noisy mostly because of the pressure sensors performance", Fig. 6.8); the simulator's sensor
#: model (softpad.sim, docs/box-and-simulator.md) uses it.
SENSOR_NOISE_STD_PA = 8.0
#: Stationary rms of the sensor's slow drift, Pa (the same sensor model).
SENSOR_DRIFT_STD_PA = 3.0
#: Resolution of the box's converter, Pa: a 12-bit converter over a 10 kPa span (the same model).
SENSOR_QUANTIZATION_PA = 10e3 / 4096
#: Variance of one pressure reading, Pa^2: white noise, drift and quantisation of the sensor
#: model (published as ``FluidPressure.variance``).
SENSOR_VARIANCE_PA2 = (
    SENSOR_NOISE_STD_PA**2 + SENSOR_DRIFT_STD_PA**2 + SENSOR_QUANTIZATION_PA**2 / 12
)
#: t_o, object-detection threshold on the increment, Pa (0.05 kPa detects a 12.6 g Duplo brick).
OBJECT_THRESHOLD_PA = 50.0
#: t_g, gripper-contact threshold on the filtered increment, Pa (0.09 kPa).
CONTACT_THRESHOLD_PA = 90.0
#: Length of the running average of the pressure readings, samples (10).
FILTER_WINDOW = 10

# --- Planning (Section 6.2.1.3) --------------------------------------------------------------
#: c_s, safety shift of corner-shaped objects, module units (0.2).
SAFETY_SHIFT = 0.2

# --- Robot and gripper (Section 6.3) ---------------------------------------------------------
#: Approach (descent) speed of the arm towards the pad, m/s (0.05 m/s).
APPROACH_SPEED_M_S = 0.05
#: Time the lifted object is held, s (15 s).
HOLD_S = 15.0
#: Length of the gripper's fingers, m (9.5 cm).
FINGER_LENGTH_M = 0.095
#: The three mountings of the Sawyer's parallel gripper, name -> (max width, min width), m
#: (Section 6.3: 10/4, 6/2 and 4/0 cm).
GRIPPER_MOUNTINGS_M: dict[str, tuple[float, float]] = {
    "10/4": (0.10, 0.04),
    "6/2": (0.06, 0.02),
    "4/0": (0.04, 0.0),
}
#: Fingertip size across the closing direction, m. The thesis gives no number, only that the tips
#: were "very small for the chosen gripper" (Section 6.3). 16 mm is the Rethink Robotics
#: electric parallel gripper's basic hard tip (the Sawyer's standard tip): collision box
#: 16 x 6.5 x 37 mm in RethinkRobotics/intera_common,
#: intera_tools_description/urdf/electric_gripper/fingers/basic_hard_tip.xacro.
FINGERTIP_WIDTH_M = 0.016
#: Fingertip size along the closing direction, m: 6.5 mm, the same basic hard tip (source above).
FINGERTIP_THICKNESS_M = 0.0065

#: Closing speed of the gripper's opening, m/s (each jaw moves at half of it). Not in the thesis;
#: chosen equal to the approach speed so that the jaws meet an object no harder than the
#: fingers meet the pad.
JAW_SPEED_M_S = APPROACH_SPEED_M_S

# --- Experiment 2 (Section 6.3, Table 6.1) ---------------------------------------------------
#: Trials per object (5).
TRIALS_PER_OBJECT = 5
#: Overall success of Experiment 2 (52 of 55).
EXPERIMENT_2_SUCCESSES = (52, 55)

#: Largest rotation of a grasp direction, rad (theta is reported in (-pi/2, pi/2]; DESIGN.md).
THETA_RANGE_RAD = (-math.pi / 2, math.pi / 2)

__all__ = [
    "ADJUST_TOLERANCE_PA",
    "APPROACH_SPEED_M_S",
    "BOX_CHANNELS",
    "CHAMBER_GAP_VOLUME_M3",
    "CHAMBER_SIDE_M",
    "CONTACT_THRESHOLD_PA",
    "EXPERIMENT_2_SUCCESSES",
    "FILTER_WINDOW",
    "FINGERTIP_THICKNESS_M",
    "FINGERTIP_WIDTH_M",
    "FINGER_LENGTH_M",
    "GRIPPER_MOUNTINGS_M",
    "HOLD_S",
    "JAW_SPEED_M_S",
    "LAYER_THICKNESS_M",
    "MAX_PRESSURE_PA",
    "MODULE_PITCH_M",
    "OBJECT_THRESHOLD_PA",
    "P0_PA",
    "P0_RANGE_PA",
    "PROTOTYPE_COLS",
    "PROTOTYPE_ROWS",
    "REFERENCE_READS",
    "SAFETY_SHIFT",
    "SEAM_WIDTH_M",
    "THETA_RANGE_RAD",
    "TRIALS_PER_OBJECT",
    "TUBING_VOLUME_M3",
]
