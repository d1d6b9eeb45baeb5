/* report.h — the structure behind sb_validate_report (private to
 * lib/validate): records, and per case its notes, status and timing. */
#ifndef SB_VALIDATE_REPORT_H
#define SB_VALIDATE_REPORT_H

#include <stddef.h>
#include <smolbridge/stats.h>

struct sbv_case_log {
  const char *case_name;
  size_t first, count;   /* its records: recs[first .. first+count) */
  char *notes;           /* Markdown lines (malloc'd, may be NULL) */
  double seconds;
  int status;            /* the case function's return value */
  char message[256];     /* sb_last_error() when status != 0 */
};

struct sb_validate_report {
  sb_comparison *recs;
  size_t nrecs, caprecs;
  struct sbv_case_log *cases;
  size_t ncases, capcases;
  /* write mode (ini.c): the configuration written last, the summary.json
   * field its next record comes from, files written, runs left out */
  char ini_path[1100];
  char ini_field[96];
  char ini_next[128];      /* file name of the next first-hit run */
  size_t nini;
  char ini_skipped[2048];
};

/* Start the log of a case: later sbv_add/sbv_note calls belong to it. */
int sbv_report_begin_case(struct sb_validate_report *rep, const char *name);
void sbv_report_end_case(struct sb_validate_report *rep, int status,
                         double seconds);

#endif /* SB_VALIDATE_REPORT_H */
