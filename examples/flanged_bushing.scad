// A flanged bushing: a sleeve with a flange at one end, a bore through both, a
// chamfer at the bore's mouth and three bolt holes in the flange. Its profile is
// turned about the z axis with rotate_extrude.
bore = 12;          // bore diameter
sleeve_od = 18;     // sleeve outer diameter
sleeve_len = 20;
flange_od = 36;
flange_t = 4;
chamfer = 1;
bolt_d = 3.4;       // M3 clearance
bolt_circle = 27;   // diameter of the bolt circle
$fn = 64;

difference() {
  rotate_extrude()
    polygon([[bore / 2 + chamfer, 0], [flange_od / 2, 0], [flange_od / 2, flange_t],
             [sleeve_od / 2, flange_t], [sleeve_od / 2, sleeve_len], [bore / 2, sleeve_len],
             [bore / 2, chamfer]]);
  for (a = [0 : 120 : 359])
    rotate([0, 0, a]) translate([bolt_circle / 2, 0, -1]) cylinder(h = flange_t + 2, d = bolt_d, $fn = 24);
}
