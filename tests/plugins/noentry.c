/* Fixture: a shared object without the entry symbol. */
#include <s42_plugin.h>

S42_EXPORT int not_an_entry(void);
S42_EXPORT int not_an_entry(void) { return 42; }
