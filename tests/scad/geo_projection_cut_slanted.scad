// Sections of a drilled sphere tilted by 30 degrees about [1, 1, 0], cut by z = 0,
// extruded and tilted back (examples/Old/example021.scad's demo_cut). Rounding the
// tilted solid's section left two of its points a unit apart with their edges
// touching, which linear_extrude() refused; the section is now made a valid shape by
// the planar Boolean. OpenSCAD's volume is compared by scripts/openscad_compare.sh.
// expect valid
// expect counts: volumes=14
module thing() {
  $fa = 30;
  difference() {
    sphere(r = 25);
    cylinder(h = 62.5, r1 = 12.5, r2 = 6.25, center = true);
    rotate(90, [1, 0, 0]) cylinder(h = 62.5, r1 = 12.5, r2 = 6.25, center = true);
    rotate(90, [0, 1, 0]) cylinder(h = 62.5, r1 = 12.5, r2 = 6.25, center = true);
  }
}
for (i = [-20 : 5 : 20])
  rotate(-30, [1, 1, 0]) translate([0, 0, -i])
    linear_extrude(center = true, height = 0.5) projection(cut = true)
      translate([0, 0, i]) rotate(30, [1, 1, 0]) thing();
