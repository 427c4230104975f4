// The type tests.
// expect echo: ECHO: true, true, true, true, true, true, false, false
echo(is_num(1), is_list([]), is_function(function(x) x), is_string(""), is_bool(true),
     is_undef(undef), is_num(0 / 0), is_list("ab"));
