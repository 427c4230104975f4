// include<> splices the file in: its variables and modules are visible.
// expect echo: ECHO: 3
// expect volume: 27
include <lib/inc_lib.scad>
echo(lib_size);
lib_box();
