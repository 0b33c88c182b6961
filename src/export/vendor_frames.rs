//! The set's two frames as KUKA KRL and ABB RAPID data (issue 34,
//! `krl-frames`, `rapid-frames`): what a base-only or hand–eye-only
//! recalibration changes on those controllers.
//!
//! - KRL: `FRAME {X, Y, Z, A, B, C}` in mm and degrees, `R = Rz(A) Ry(B)
//!   Rx(C)` (KUKA's Z-Y-X order). `$ROBROOT` is the robot's root in WORLD,
//!   here the set's world frame (the board, or the tracker): the set's
//!   `target_to_base`/`instrument_to_base` as is. `TOOL_DATA[1]` (what
//!   `$TOOL` takes) is the camera or probe in the flange frame.
//! - RAPID: a `wobjdata`'s user frame is a frame in the robot's world,
//!   which on an ABB cell is the base frame unless the cell sets another,
//!   so `wobjdata` holds the set's world frame (board, tracker) in the base
//!   frame — the inverse of `target_to_base` — and `tooldata` the tool in
//!   the flange (`tool0`) frame; mm and a unit quaternion `q1..q4`, scalar
//!   first (`q1 >= 0`).

use std::fmt::Write;

use robocal_calib::geometry::Pose;

use super::header::ExportHeader;
use crate::domain::FrameNames;

/// ABB's `tool0` load: robocal identifies no load, and a tooldata with a
/// zero mass is refused by the controller; the cell enters its own.
const PLACEHOLDER_LOAD: &str = "[0.001, [0, 0, 0.001], [1, 0, 0, 0], 0, 0, 0]";

/// A KRL FRAME aggregate of `pose`.
pub fn krl_frame(pose: &Pose) -> String {
    let t = pose.translation.vector;
    let (c, b, a) = pose.rotation.euler_angles();
    format!(
        "{{X {},Y {},Z {},A {},B {},C {}}}",
        t.x,
        t.y,
        t.z,
        a.to_degrees(),
        b.to_degrees(),
        c.to_degrees()
    )
}

/// A RAPID `pose` aggregate `[[x, y, z], [q1, q2, q3, q4]]`.
pub fn rapid_pose(pose: &Pose) -> String {
    let t = pose.translation.vector;
    let q = pose.rotation.quaternion();
    let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
    format!(
        "[[{}, {}, {}], [{}, {}, {}, {}]]",
        t.x,
        t.y,
        t.z,
        sign * q.w,
        sign * q.i,
        sign * q.j,
        sign * q.k
    )
}

/// The KRL data: `$ROBROOT` and `TOOL_DATA[1]`.
pub fn write_krl(
    header: &ExportHeader,
    frames: FrameNames,
    world_to_base: &Pose,
    flange_to_tool: &Pose,
) -> String {
    let mut s = header.comment("krl-frames", ";");
    let _ = writeln!(
        s,
        ";\n; FRAME {{X, Y, Z, A, B, C}}: mm and degrees, R = Rz(A) Ry(B) Rx(C).\n\
         ; $ROBROOT (in $MACHINE.DAT): the robot's root in WORLD, WORLD being the\n\
         ; set's {world} frame ({wtb}).\n\
         FRAME $ROBROOT={}\n\
         ; TOOL_DATA[1] (in $CONFIG.DAT): the {end} in the flange frame ({fte});\n\
         ; a program selects it with $TOOL=TOOL_DATA[1].\n\
         TOOL_DATA[1]={}",
        krl_frame(world_to_base),
        krl_frame(flange_to_tool),
        world = frames.world,
        wtb = frames.world_to_base,
        end = frames.end,
        fte = frames.flange_to_end,
    );
    s
}

/// The RAPID module `robocal_frames`: `wobjdata` and `tooldata` declarations.
pub fn write_rapid(
    header: &ExportHeader,
    frames: FrameNames,
    world_to_base: &Pose,
    flange_to_tool: &Pose,
) -> String {
    let mut s = String::from("MODULE robocal_frames\n");
    s.push_str(&header.comment("rapid-frames", "!"));
    let _ = writeln!(
        s,
        "!\n! pose [[x, y, z], [q1, q2, q3, q4]]: mm, unit quaternion scalar first.\n\
         ! wobjdata: uframe is the set's {world} frame in the robot's base frame\n\
         ! (the ABB world frame when the cell sets none), the inverse of {wtb}.\n\
         PERS wobjdata robocal_{world} := [FALSE, TRUE, \"\", {}, [[0, 0, 0], [1, 0, 0, 0]]];\n\
         ! tooldata: the {end} in the flange (tool0) frame ({fte}); the load is\n\
         ! tool0's placeholder: robocal does not identify it, enter the tool's own.\n\
         PERS tooldata robocal_{end} := [TRUE, {}, {PLACEHOLDER_LOAD}];\n\
         ENDMODULE",
        rapid_pose(&world_to_base.inverse()),
        rapid_pose(flange_to_tool),
        world = frames.world,
        wtb = frames.world_to_base,
        end = frames.end,
        fte = frames.flange_to_end,
    );
    s
}
