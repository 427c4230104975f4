// A box: volume, area and counts.
// expect volume: 24
// expect area: 52
// expect counts: vertices=8 edges=12 faces=6 volumes=1
// expect bbox: [0, 0, 0] [2, 3, 4]
cube([2, 3, 4]);
