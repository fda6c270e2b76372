#include "suites.h"
Suite *suite_compile(void) { return suite_create("compile"); }
Suite *suite_vm(void) { return suite_create("vm"); }
Suite *suite_machine(void) { return suite_create("machine"); }
Suite *suite_operator(void) { return suite_create("operator"); }
Suite *suite_session(void) { return suite_create("session"); }
