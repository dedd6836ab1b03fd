/* datafmt: the two data formats tarn writes figures in, a value at a time
 * into a strbuf: JSON (`tarn bench`'s bench.json, `tarn compare --json`)
 * and CSV (bench.csv, passes.csv, `tarn compare --csv`). One spelling of a
 * number for both: %.9g (a float's digits and then some); not measured
 * (NaN) is JSON null and an empty CSV field; infinities are "inf"/"-inf". */
#ifndef TARN_DATAFMT_H
#define TARN_DATAFMT_H

#include <stdbool.h>

#include "strbuf.h"

/* A JSON string: quotes, backslashes and control characters escaped. */
void json_put_str(strbuf *o, const char *s);
/* A JSON number (NaN: null; an infinity: the string "inf" or "-inf"). */
void json_put_num(strbuf *o, double v);

/* A CSV field: quoted (a quote doubled) always when quote is true, else
 * only when it holds a comma, quote or line break (RFC 4180). */
void csv_put_str(strbuf *o, const char *s, bool quote);
/* A CSV number (NaN: an empty field). */
void csv_put_num(strbuf *o, double v);

#endif
