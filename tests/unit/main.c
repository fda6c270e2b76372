/* The unit test runner: every suite of tests/unit under one SRunner.
 * Exits non-zero when any test fails. */
#include "suites.h"
#include <stdlib.h>

int main(void)
{
  SRunner *sr = srunner_create(suite_lex());
  srunner_add_suite(sr, suite_parse());
  srunner_add_suite(sr, suite_compile());
  srunner_add_suite(sr, suite_vm());
  srunner_add_suite(sr, suite_machine());
  srunner_add_suite(sr, suite_operator());
  srunner_add_suite(sr, suite_session());
  srunner_add_suite(sr, suite_screen());
  srunner_add_suite(sr, suite_plugin());
  srunner_add_suite(sr, suite_toolmodel());
  srunner_add_suite(sr, suite_tuitext());
  srunner_add_suite(sr, suite_modbus());
  srunner_add_suite(sr, suite_travel());
  srunner_add_suite(sr, suite_state());
  srunner_add_suite(sr, suite_param());
  srunner_add_suite(sr, suite_verify());
  srunner_add_suite(sr, suite_words());
  srunner_add_suite(sr, suite_lathe());
  srunner_add_suite(sr, suite_u22());
  srunner_add_suite(sr, suite_lplot());
  srunner_add_suite(sr, suite_plot());
  srunner_add_suite(sr, suite_mrun());
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
