// An L bracket: a base plate and an upright web, each with two mounting holes, and a
// triangular gusset between them. All sizes in mm; change them with -D (e.g.
// `cellforge build bracket.scad -D thickness=6 -o bracket.stl`).
width = 40;       // along x
depth = 30;       // base plate, along y
height = 35;      // upright web, along z
thickness = 5;
hole_d = 6.5;     // an M6 clearance hole
gusset = 18;      // the gusset's legs
$fn = 40;

module holes_along_x(y, z, axis) {
  for (x = [width * 0.25, width * 0.75])
    translate([x, y, z]) rotate(axis) cylinder(h = 3 * thickness, d = hole_d, center = true);
}

difference() {
  union() {
    cube([width, depth, thickness]);                         // base plate
    cube([width, thickness, height]);                        // upright web
    translate([width / 2 - thickness / 2, 0, 0])             // gusset
      rotate([90, 0, 90]) linear_extrude(thickness)
        polygon([[thickness, thickness], [gusset + thickness, thickness], [thickness, gusset + thickness]]);
  }
  holes_along_x(depth * 0.6 + thickness * 0.4, thickness / 2, [0, 0, 0]);   // through the base
  holes_along_x(thickness / 2, height * 0.65 + thickness * 0.35, [90, 0, 0]); // through the web
}
