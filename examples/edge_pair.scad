// Non-manifold on purpose: two blocks that share exactly one edge. The union is one
// valid result whose shared edge has four faces around it; most mesh tools call
// such a file broken, cellforge keeps it as it is.
cube(10);
translate([10, 10, 0]) cube(10);
