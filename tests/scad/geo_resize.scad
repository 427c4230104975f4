// resize to x = 4 with auto: every axis scales by 4.
// expect volume: 384
resize([4, 0, 0], auto = true) cube([1, 2, 3]);
