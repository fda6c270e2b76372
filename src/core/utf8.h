/* UTF-8 for the front ends: a strict decoder (overlong forms, surrogates
 * and anything past U+10FFFF are not characters), an encoder, and the
 * Cyrillic capitals that the seeds' programs write for Latin addresses
 * (А В С Е Н К М О Р Т Х: the manuals were typed on Cyrillic keyboards). */
#ifndef S42_UTF8_H
#define S42_UTF8_H

#include <stddef.h>
#include <stdint.h>

#define UTF8_BAD 0xFFFD    /* what a byte that is not UTF-8 decodes to (one byte) */

/* The code point at s (left bytes, left >= 1); *len its length.  A byte
 * that does not start a valid sequence is UTF8_BAD of length 1. */
int32_t utf8_decode(const unsigned char *s, size_t left, size_t *len);
/* c into buf (4 bytes at most); the length. */
int utf8_encode(int32_t c, char *buf);
/* The Latin capital a Cyrillic look-alike stands for ('A' for А), or 0. */
int utf8_latin_lookalike(int32_t c);

#endif
