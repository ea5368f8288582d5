/* Reading back the harness's CSV files (cmp_csv.c), for the report. */
#ifndef CMP_CSV_H
#define CMP_CSV_H


#define CMP_CSV_MAX_COLS 64

typedef struct cmp_csv {
    char *text;                          /* the file, split in place */
    const char *header[CMP_CSV_MAX_COLS];
    int ncols;
    long nrows;
    long bad_rows;                       /* rows with the wrong field count */
    char **cells;                        /* nrows x ncols */
} cmp_csv;

/* 0, or -1 if the file cannot be read or has no header. */
int cmp_csv_read(const char *path, cmp_csv *t);
void cmp_csv_free(cmp_csv *t);
/* Column index by header name, -1 if absent. */
int cmp_csv_col(const cmp_csv *t, const char *name);
/* Field as text ("" out of range) or number (NaN if not a number). */
const char *cmp_csv_str(const cmp_csv *t, long row, int col);
double cmp_csv_num(const cmp_csv *t, long row, int col);

#endif
