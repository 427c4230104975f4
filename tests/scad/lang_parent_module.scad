// parent_module() and $parent_modules name the module calls above.
// expect echo: ECHO: "inner", "outer", 2
module inner() echo(parent_module(0), parent_module(1), $parent_modules);
module outer() inner();
outer();
