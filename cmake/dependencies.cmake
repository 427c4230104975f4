# External libraries used by individual layers (SQLite, libpq, lib3mf) are found here.
