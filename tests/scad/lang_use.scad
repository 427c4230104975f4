// use<> imports modules and functions only; the library's variables stay its own.
// expect echo: ECHO: 6, undef
// expect warning: unknown variable 'use_secret'
// expect volume: 8
use <lib/use_lib.scad>
echo(use_double(3), use_secret);
use_cube();
