// Two squares of side 2 turned 45 degrees apart: an octagon of inradius 1,
// area 8 tan(22.5), times height 2.
// expect volume: 6.627416997969521
intersection_for (a = [0, 45]) rotate([0, 0, a]) cube(2, center = true);
