// A spur gear: a hub disc with trapezoidal teeth (a straight-flank approximation of
// the involute), a bore with a keyway, extruded to its face width.
teeth = 18;
module_m = 2;              // the gear module: pitch diameter = teeth * module
face_width = 8;
bore = 8;
key = 3;
pitch_r = teeth * module_m / 2;
root_r = pitch_r - 1.25 * module_m;
tip_r = pitch_r + module_m;
pitch_angle = 360 / teeth;

module tooth() {
  // Half-widths at the root and the tip, as angles seen from the centre.
  a_root = pitch_angle * 0.3;
  a_tip = pitch_angle * 0.14;
  polygon([[root_r * cos(-a_root), root_r * sin(-a_root)], [tip_r * cos(-a_tip), tip_r * sin(-a_tip)],
           [tip_r * cos(a_tip), tip_r * sin(a_tip)], [root_r * cos(a_root), root_r * sin(a_root)]]);
}

linear_extrude(height = face_width)
  difference() {
    union() {
      circle(r = root_r + 0.01, $fn = teeth * 4);
      for (i = [0 : teeth - 1]) rotate(i * pitch_angle) tooth();
    }
    circle(d = bore, $fn = 32);
    translate([bore / 2 - 0.5, -key / 2]) square([key, key]);
  }
