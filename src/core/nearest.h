/* "Did you mean": the closest of a list of names to a word typed wrong
 * (options, commands, operator actions and keys). */
#ifndef S42_NEAREST_H
#define S42_NEAREST_H

#include <stddef.h>

/* Edit distance of a and b (each at most 63 characters; longer: 99),
 * counting a swap of two neighbours as one edit (optimal string alignment). */
int word_distance(const char *a, const char *b);
/* The closest of the names (within a third of the word's length, at least
 * 1 edit), or NULL. */
const char *nearest_word(const char *word, const char *const *names, size_t n);

#endif
