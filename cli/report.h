/* report.h — the validation report behind sbv_report (cli/report.c). */
#ifndef SB_CLI_REPORT_H
#define SB_CLI_REPORT_H

#include <stdio.h>
#include "cases.h"

struct sbv_case_log {
  const char *case_name;
  size_t first, count;   /* its records: recs[first .. first+count) */
  char *notes;           /* Markdown lines (malloc'd, may be NULL) */
  double seconds;
  int status;            /* the case function's return value */
};

struct sbv_report {
  sb_comparison *recs;
  size_t nrecs, caprecs;
  struct sbv_case_log *cases;
  size_t ncases, capcases;
};

sbv_report *sbv_report_alloc(void);
void sbv_report_free(sbv_report *rep);
/* Start the log of a case: later sbv_add/sbv_note calls belong to it. */
int sbv_report_begin_case(sbv_report *rep, const char *name);
void sbv_report_end_case(sbv_report *rep, int status, double seconds);

/* Outputs. */
void sbv_report_print_table(const sbv_report *rep, FILE *out);
int sbv_report_write_csv(const sbv_report *rep, const char *path);
int sbv_report_write_markdown(const sbv_report *rep, const char *path,
                              const char *mode, unsigned long seed);
size_t sbv_report_nfail(const sbv_report *rep);

#endif /* SB_CLI_REPORT_H */
