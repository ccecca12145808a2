// The numbers of one humanoid walking style for the gait controller (experts/gait_controller.h):
// every knob a top-level scalar, so that a tuner sets one by name through JSON
// (`json j = p; j[name] = x; p = j.get<GaitParameters>()`), and a style file
// (configs/humanoid_styles/...) is `{"parameters": {...}}`, keys left out taking the defaults.
// The defaults are the walk that CMA-ES tuned on the feasibility prototype
// (../shared/reference/humanoid_gait, params/walk.params), with its sagittal offset re-expressed
// against the desired speed so that at speed = 1.25 m/s the placement law is the prototype's.
//
// Frames: the heading frame is the world turned about z by the commanded heading (x forward, y to
// the body's left). "Stance side" and "swing side" are the legs' sides; a sign s is +1 for the
// left leg, -1 for the right. Angles in rad, lengths in m, times in s, gains in N m/rad and
// N m s/rad (torques at the joint, before the motor's gear).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace vaegail {

struct GaitParameters {
  // ---- state machine: one state per step
  double step_min_time = 0.33493;  // s: the swing foot's contact swaps the legs from then on; also the swing's duration
  double step_max_time = 0.4522;   // s: the legs swap at this time in a step, contact or not

  // ---- commands
  double speed = 1.25;          // m/s: forward centre-of-mass speed the sagittal placement aims for
  double heading = 0.0;         // rad: direction of travel, from world x towards world y
  double turn_rate = 0.5;       // rad/s: the commanded heading turns from the reset's facing (world x) to
                                //   `heading` at this rate (a sudden turn trips the walk)
  double heading_wander = 0.0;  // rad: amplitude of a sinusoidal wander of the heading ("drunk")
  double wander_period = 4.0;   // s: period of that wander
  double sway_speed = 0.0;      // m/s: lateral COM speed towards the new stance foot that each placement aims for;
                                //   > 0 narrows the steps and swings the body wider from side to side

  // ---- foot placement (balance feedback, Coros 2010), in the heading frame, from the COM's
  // position d and velocity v relative to the stance ankle:
  //   x_f = x_stance + place_dx d_x + place_vx (v_x - speed) + place_offset_x
  //   y_f = y_stance + place_dy d_y + place_vy (v_y - s_swing sway_speed) + s_swing step_width
  double place_dx = 1.0661;           // 1: gain on the COM's forward offset
  double place_vx = 0.20829;          // s: gain on the forward speed error
  double place_offset_x = 0.0832125;  // m: forward offset (the prototype's -0.17715 + 0.20829 * 1.25)
  double place_dy = 0.88961;          // 1: gain on the COM's lateral offset
  double place_vy = 0.32497;          // s: gain on the lateral speed error
  double step_width = 0.099165;       // m: outward offset of the swing foot

  // ---- swing foot path to the target, phase = time in step / step_min_time
  double swing_height = 0.15475;          // m: ankle lift above its standing height, a half sine
  double swing_descent_phase = 0.8762;    // phase at which the lift's half sine ends
  double swing_reach_phase = 0.71306;     // phase at which the foot is over the target (smoothstep)
  double swing_end_height = -0.050195;    // m: ankle target height reached at phase 1 past the half sine
                                          //   (< 0: the foot keeps going down until it lands)
  double toe_out = 0.0;                   // rad: swing thigh's yaw outwards
  double swing_ankle = -0.23465;          // rad: swing foot pitch from level before step_min_time (+ toes down)
  double swing_ankle_late = 0.0;          // rad: the same after step_min_time

  // ---- stance leg
  double stance_knee = 0.074773;   // rad: stance knee flexion
  double stance_ankle = -0.029086; // rad: stance foot pitch from flat
  double hip_support = 0.89426;    // share of the static torque holding the body above the stance hip
  double knee_support = 1.0;       // share of the static torque holding the body above the stance knee
  double ankle_support = 0.0;      // share of the static torque holding the body above the stance ankle
  double support_ramp = 0.1;       // s: after a swap, while the old stance foot is still down, the shares
                                   //   ramp from half to full over this

  // ---- torso, in the heading frame
  double pelvis_pitch = 0.075841;  // rad: pelvis pitched forward
  double pelvis_roll = -0.077509;  // rad: pelvis rolled towards the stance side
  double back_pitch = 0.0;         // rad: forward bend over the three back joints (stooped, old)
  double back_roll = -0.15203;     // rad: thorax lean towards the stance side in the world (the walk's < 0 leans away,
                                   //   with the pelvis's drop rather than against it)
  double back_roll_filter = 0.05;  // s: time constant of that lean's target

  // ---- PD gains
  double kp_swing_hip = 466.87, kd_swing_hip = 32.171;  // swing femur's world orientation
  double kp_torso = 709.92, kd_torso = 67.224;          // pelvis's world orientation
  double kp_knee = 230.19, kd_knee = 20.0;
  double kp_ankle = 26.846, kd_ankle = 4.0;
  double kp_back = 300.0, kd_back = 20.0;
  double kp_arm = 60.0, kd_arm = 4.0;                   // clavicles, shoulders, elbows
  double kp_neck = 40.0, kd_neck = 3.0;                 // neck and head
  double kp_distal = 5.0, kd_distal = 0.3;              // wrists, hands, fingers; toes at 4 times

  // ---- arms
  double arm_abduction = 0.0;  // rad: shoulders out to the side
  double arm_flexion = 0.0;    // rad: shoulders forward
  double arm_twist = 0.0;      // rad: shoulders' twist outwards
  double elbow = 0.3;          // rad: elbow flexion
  double arm_swing = 0.0;      // 1: shoulder flexion per rad of the opposite thigh's forward pitch
};

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(GaitParameters, step_min_time, step_max_time, speed, heading,
                                                turn_rate, heading_wander, wander_period, sway_speed, place_dx, place_vx,
                                                place_offset_x, place_dy, place_vy, step_width, swing_height,
                                                swing_descent_phase, swing_reach_phase, swing_end_height, toe_out,
                                                swing_ankle, swing_ankle_late, stance_knee, stance_ankle, hip_support,
                                                knee_support, ankle_support, support_ramp, pelvis_pitch, pelvis_roll,
                                                back_pitch, back_roll, back_roll_filter, kp_swing_hip, kd_swing_hip,
                                                kp_torso, kd_torso, kp_knee, kd_knee, kp_ankle, kd_ankle, kp_back,
                                                kd_back, kp_arm, kd_arm, kp_neck, kd_neck, kp_distal, kd_distal,
                                                arm_abduction, arm_flexion, arm_twist, elbow, arm_swing)

// Parameters from JSON, keys left out taking the defaults. Throws (one line naming `where` and
// the key) on a key that is not a parameter, a value that is not a number, or numbers that cannot
// run a step (step times, turn_rate or wander_period not > 0, swing phases not in (0, 1]).
GaitParameters gait_parameters_from_json(const nlohmann::json& parameters, const std::string& where);

// A style file: its "parameters" object (other top-level keys, e.g. a tuner's record, are left
// alone). Throws naming the file when it is missing, malformed or has no "parameters".
GaitParameters read_gait_style(const std::string& path);

}  // namespace vaegail
