// Used by lang_use.scad: only the module and the function are imported.
use_secret = 42;
function use_double(x) = 2 * x;
module use_cube() cube(2);
cube(100);  // not instantiated by use<>
