// $ variables follow the calls (dynamic scope); plain variables the text (lexical).
// expect echo: ECHO: 2, 1
// expect echo: ECHO: 1, 1
$v = 1;
w = 1;
module a() echo($v, w);
module b() { $v = 2; w = 2; a(); }
b();
a();
