# boolean/: its stages run on threads (Options::threads).
find_package(Threads REQUIRED)
target_link_libraries(${layer} PUBLIC Threads::Threads)
