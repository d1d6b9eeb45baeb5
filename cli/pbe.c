/* pbe.c — `smolbridge pbe`: solve the Smoluchowski population balance and
 * write the size distribution and its moments as CSV. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <smolbridge/common.h>
#include <smolbridge/kernel.h>
#include <smolbridge/pbe.h>

#include "cli.h"

static void usage(FILE *out)
{
  fprintf(out,
"Usage: smolbridge pbe --kernel NAME [--param KEY=VALUE ...] [--v1 V1]\n"
"         --n0 N0 [--init mono|exp] [--v0 V0] [--method discrete|sectional]\n"
"         [--sizes K] --times T1,T2,... --out FILE.csv [--plot FILE.png]\n"
"         [--ratio R] [--rtol TOL] [--atol TOL] [--linsol auto|dense|gmres|gmres-diag]\n"
"         [--gain auto|direct|fft] [-q]\n"
"\n"
"Integrate the Smoluchowski coagulation equation with CVODE (BDF) from a\n"
"monodisperse (all particles of volume V1) or exponential (mean volume V0)\n"
"start, and write FILE.csv with header t,k,v,n (time, size index, volume,\n"
"number concentration; sectional: pivot volume and number in the section;\n"
"discrete: the lumped tail beyond size K as the row k = K+1 at its mean\n"
"volume) and FILE-moments.csv with header t,M0,M1,M2,tail_n,tail_M1\n"
"(M_j = sum v^j n; the tail's number and volume, 0 when sectional).  The\n"
"M1 drift (conservation check) is printed on stderr.\n"
"\n"
"Kernels (--kernel) and their parameters (--param KEY=VALUE, SI units):\n"
"  constant        K (m^3/s)            K\n"
"  additive        K (1/s)              K (v_i + v_j)\n"
"  multiplicative  K (1/(m^3 s))        K v_i v_j\n"
"  brownian-co     T (K), mu (Pa s)     continuum Brownian\n"
"  brownian-fm     T, rho_p (kg/m^3)    free-molecular Brownian\n"
"  brownian-tr     T, mu, rho_p, lambda (m, gas mean free path; 0: none)\n"
"  gravity         rho_p, rho_f, mu, g (m/s^2)\n"
"  shear           G (1/s)\n"
"  saffman-turner  eps (m^2/s^3), nu (m^2/s)\n"
"  brownian-turb   T, mu, eps, nu\n"
"  kinetic         T, rho_p             hard spheres, mass rho_p v\n"
"  abrahamson      u2 (m^2/s^2)         inertial, velocity variance u2\n"
"  diffusion       b2 (m^2/s)           pure diffusion, B_pos^2 = b2\n"
"Defaults: K = 1, water at 20 C (T 293.15, mu 1.002e-3, rho_f 998.2,\n"
"nu 1.004e-6), rho_p 1000, lambda 0, g 9.80665, G 1, eps 1e-4, u2 1,\n"
"b2 1e-12.\n"
"Physical kernels take volumes in m^3 (radius (3v/4pi)^(1/3)).  A\n"
"--param the kernel does not use is ignored with a warning; one given\n"
"twice is an error.\n"
"\n"
"Options:\n"
"  --kernel NAME a kernel above (required)\n"
"  --param K=V   a parameter of the kernel (repeatable)\n"
"  --out FILE    the size file FILE (required; also -o FILE); the moments\n"
"                go to FILE without .csv, plus -moments.csv\n"
"  --v1 V1       monomer volume / smallest pivot (default 1)\n"
"  --n0 N0       initial number concentration (required; any N0 > 0 whose\n"
"                rate N0 K(V1, V1) is a normal double: pbe solves for n/N0\n"
"                with the kernel N0 K)\n"
"  --init        mono (default) or exp; --v0 V0 mean volume (default\n"
"                10 V1 discrete, 1e4 V1 sectional)\n"
"  --method      discrete (default; sizes k V1, k = 1..K, plus a lumped\n"
"                tail) or sectional (fixed pivots V1 R^i, i = 0..K-1)\n"
"  --sizes K     number of sizes or sections, 2 to 1e6 (default 100)\n"
"  --ratio R     sectional pivot ratio (default 10^(12/(K-1)): 12 decades)\n"
"  --times LIST  comma-separated increasing output times (required)\n"
"  --rtol, --atol  CVODE tolerances (default 1e-8, automatic)\n"
"  --linsol      auto (= gmres-diag), dense, gmres or gmres-diag\n"
"  --gain        discrete gain of the constant, additive and multiplicative\n"
"                kernels: auto (FFT for constant from 4096 sizes at the\n"
"                default atol or looser), direct or fft (docs/pbe.md)\n"
"  --plot FILE   PNG of n(v) at each output time (needs gnuplot)\n"
"  -q, --quiet   no progress messages\n"
"  -h, --help    this help\n"
"\n"
"Example: smolbridge pbe --kernel constant --param K=1 --n0 1 --init mono\n"
"           --method discrete --sizes 200 --times 0.1,1,10 --out c.csv\n");
}

/* The --param keys each kernel reads (sb_kernel_spec_fn; the others are
 * warned about, as --ratio and --v0 where they do not apply). */
static const char *const kernel_keys[SB_KERNEL_NTYPES] = {
    [SB_KERNEL_CONSTANT] = "K",
    [SB_KERNEL_ADDITIVE] = "K",
    [SB_KERNEL_MULTIPLICATIVE] = "K",
    [SB_KERNEL_BROWNIAN_CO] = "T, mu",
    [SB_KERNEL_BROWNIAN_FM] = "T, rho_p",
    [SB_KERNEL_BROWNIAN_TR] = "T, mu, rho_p, lambda",
    [SB_KERNEL_GRAVITY] = "rho_p, rho_f, mu, g",
    [SB_KERNEL_SHEAR] = "G",
    [SB_KERNEL_SAFFMAN_TURNER] = "eps, nu",
    [SB_KERNEL_BROWNIAN_TURB] = "T, mu, eps, nu",
    [SB_KERNEL_KINETIC] = "T, rho_p",
    [SB_KERNEL_ABRAHAMSON] = "u2",
    [SB_KERNEL_DIFFUSION] = "b2",
};

/* 1 if key is one of the comma-separated names of list. */
static int listed(const char *list, const char *key)
{
  size_t n = strlen(key);
  for (const char *p = list; *p;) {
    size_t m = strcspn(p, ",");
    if (m == n && !strncmp(p, key, n))
      return 1;
    p += m;
    while (*p == ',' || *p == ' ')
      p++;
  }
  return 0;
}

/* The population balance is invariant under n -> n/c, K -> c K at the
 * same times (each term is a kernel times two concentrations): pbe
 * solves for n/n0 with the kernel n0 K and writes n0 times the result,
 * so that CVODE sees concentrations of order 1 whatever the unit of n0
 * (its default absolute tolerance, 1e-14 of the largest initial
 * concentration, was below 1/DBL_MAX at --n0 1e-300: the first step
 * failed).  The constant, additive and multiplicative kernels scale K
 * itself and stay sb_kernel_spec_fn (whose FFT gain the library
 * recognises); the others go through scaled_fn. */
typedef struct {
  sb_kernel_spec spec;
  double c;
} scaled_kernel;

static double scaled_fn(double v_i, double v_j, const void *params)
{
  const scaled_kernel *s = params;
  return s->c * sb_kernel_spec_fn(v_i, v_j, &s->spec);
}

static int parse_num(const char *s, double *x)
{
  char *end;
  errno = 0;
  *x = strtod(s, &end);
  return (end == s || *end || errno == ERANGE || !isfinite(*x)) ? -1 : 0;
}

typedef struct {
  FILE *dist, *mom;
  int quiet;
  double t0;
  const sb_pbe *p;
  double n0;          /* the solved concentrations are n/n0 */
  double m1_0;        /* M1 of the initial state (of n/n0) */
  double tail_warned; /* the tail's mass share at the last warning */
  char stop[400];     /* why the output stopped the solve */
} out_ctx;

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int on_output(double t, const double *v, const double *n, size_t nb,
                     const double m[3], void *data)
{
  out_ctx *o = data;
  const double c = o->n0;
  double tn, tm;
  sb_pbe_tail(o->p, &tn, &tm);
  /* A negative concentration means the model broke down: past gelation
   * the lumped class carries the gel's mass with a vanishing number. */
  double nmin = tn;
  for (size_t k = 0; k < nb; k++)
    nmin = n[k] < nmin ? n[k] : nmin;
  if (nmin < -1e-9 * m[0] || !(m[0] > 0)) {
    snprintf(o->stop, sizeof o->stop, "at t = %g the solution has a "
             "negative number concentration (min %g, M0 = %g): the "
             "population balance broke down (gelation: a kernel growing "
             "faster than linearly in volume makes an infinite cluster in "
             "finite time); outputs stop before t = %g", t, c * nmin,
             c * m[0], t);
    return 1;
  }
  for (size_t k = 0; k < nb; k++)
    fprintf(o->dist, "%.10g,%zu,%.17g,%.17g\n", t, k + 1, v[k], c * n[k]);
  if (tn > 0)  /* the lumped tail: sizes above K, at their mean volume */
    fprintf(o->dist, "%.10g,%zu,%.17g,%.17g\n", t, nb + 1, tm / tn, c * tn);
  fprintf(o->mom, "%.10g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, c * m[0],
          c * m[1], c * m[2], c * tn, c * tm);
  /* warn when the tail first holds 1e-6 of the mass, and again each
   * time its share has grown tenfold */
  if (o->m1_0 > 0 && tm > 1e-6 * o->m1_0 &&
      tm > 10.0 * o->tail_warned * o->m1_0) {
    fprintf(stderr, "smolbridge pbe: warning: at t = %g, %.3g%% of the "
            "mass (number %g, mean volume %g) is in the lumped tail above "
            "the largest size (%g): its sizes are not resolved and M2 is "
            "a lower bound; the tail is the row k = %zu of the output; "
            "raise --sizes\n", t, 100.0 * tm / o->m1_0, c * tn, tm / tn,
            v[nb - 1], nb + 1);
    o->tail_warned = tm / o->m1_0;
  }
  if (!o->quiet)
    fprintf(stderr, "smolbridge pbe: t = %g done (%.2f s): M0 = %.6g, "
                    "M1 = %.10g, M2 = %.6g\n", t, now() - o->t0, c * m[0],
            c * m[1], c * m[2]);
  return 0;
}

int sbc_pbe_main(int argc, char **argv)
{
  static const struct option opts[] = {
      {"kernel", required_argument, NULL, 'k'},
      {"param", required_argument, NULL, 'p'},
      {"v1", required_argument, NULL, '1'},
      {"v0", required_argument, NULL, '0'},
      {"n0", required_argument, NULL, 'n'},
      {"init", required_argument, NULL, 'i'},
      {"method", required_argument, NULL, 'm'},
      {"sizes", required_argument, NULL, 's'},
      {"ratio", required_argument, NULL, 'r'},
      {"times", required_argument, NULL, 't'},
      {"out", required_argument, NULL, 'o'},
      {"plot", required_argument, NULL, 'P'},
      {"rtol", required_argument, NULL, 'R'},
      {"atol", required_argument, NULL, 'A'},
      {"linsol", required_argument, NULL, 'L'},
      {"gain", required_argument, NULL, 'G'},
      {"quiet", no_argument, NULL, 'q'},
      {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  const char *kname = NULL, *out = NULL, *plot = NULL, *times_s = NULL;
  const char *params[64];
  int nparams = 0, exp_init = 0, quiet = 0, opt;
  double v1 = 1.0, v0 = NAN, n0 = NAN, ratio = NAN, x;
  sb_pbe_config cfg;
  sb_pbe_config_init(&cfg);
  optind = 1;
#define BAD(...)                                   \
  do {                                             \
    fprintf(stderr, "smolbridge pbe: " __VA_ARGS__); \
    fputc('\n', stderr);                           \
    return 2;                                      \
  } while (0)
  while ((opt = getopt_long(argc, argv, "hqo:", opts, NULL)) != -1) {
    switch (opt) {
    case 'k': kname = optarg; break;
    case 'p':
      if (nparams == 64)
        BAD("too many --param");
      params[nparams++] = optarg;
      break;
    case '1': if (parse_num(optarg, &v1)) BAD("bad --v1 '%s'", optarg); break;
    case '0': if (parse_num(optarg, &v0)) BAD("bad --v0 '%s'", optarg); break;
    case 'n': if (parse_num(optarg, &n0)) BAD("bad --n0 '%s'", optarg); break;
    case 'r': if (parse_num(optarg, &ratio)) BAD("bad --ratio '%s'", optarg); break;
    case 'R': if (parse_num(optarg, &cfg.rtol)) BAD("bad --rtol '%s'", optarg); break;
    case 'A': if (parse_num(optarg, &cfg.atol)) BAD("bad --atol '%s'", optarg); break;
    case 'i':
      if (!strcmp(optarg, "mono")) exp_init = 0;
      else if (!strcmp(optarg, "exp")) exp_init = 1;
      else BAD("--init must be mono or exp, got '%s'", optarg);
      break;
    case 'm':
      if (!strcmp(optarg, "discrete")) cfg.method = SB_PBE_DISCRETE;
      else if (!strcmp(optarg, "sectional")) cfg.method = SB_PBE_SECTIONAL;
      else BAD("--method must be discrete or sectional, got '%s'", optarg);
      break;
    case 'L':
      if (!strcmp(optarg, "auto")) cfg.linsol = SB_PBE_LS_AUTO;
      else if (!strcmp(optarg, "dense")) cfg.linsol = SB_PBE_LS_DENSE;
      else if (!strcmp(optarg, "gmres")) cfg.linsol = SB_PBE_LS_GMRES;
      else if (!strcmp(optarg, "gmres-diag")) cfg.linsol = SB_PBE_LS_GMRES_DIAG;
      else BAD("--linsol must be auto, dense, gmres or gmres-diag, got '%s'",
               optarg);
      break;
    case 'G':
      if (!strcmp(optarg, "auto")) cfg.gain = SB_PBE_GAIN_AUTO;
      else if (!strcmp(optarg, "direct")) cfg.gain = SB_PBE_GAIN_DIRECT;
      else if (!strcmp(optarg, "fft")) cfg.gain = SB_PBE_GAIN_FFT;
      else BAD("--gain must be auto, direct or fft, got '%s'", optarg);
      break;
    case 's':
      if (parse_num(optarg, &x) || x < 2 || x > 1e6 || x != floor(x))
        BAD("--sizes needs an integer from 2 to 1e6, got '%s'", optarg);
      cfg.nsizes = (size_t)x;
      break;
    case 't': times_s = optarg; break;
    case 'o': out = optarg; break;
    case 'P': plot = optarg; break;
    case 'q': quiet = 1; break;
    case 'h': usage(stdout); return 0;
    default: usage(stderr); return 2;
    }
  }
  if (optind < argc)
    BAD("unexpected argument '%s'", argv[optind]);
  if (!kname || !out || !times_s || isnan(n0))
    BAD("--kernel, --n0, --times and --out are required (see --help)");
  /* input errors exit 2 before anything is allocated */
  if (!(n0 > 0) || !isfinite(n0))
    BAD("--n0 must be a finite number > 0, got %g", n0);
  if (!(v1 > 0) || !isfinite(v1))
    BAD("--v1 must be a finite number > 0, got %g", v1);
  if (!(cfg.rtol > 0 && cfg.rtol < 1))
    BAD("--rtol must be in (0, 1), got %g", cfg.rtol);
  if (!(cfg.atol >= 0) || !isfinite(cfg.atol))
    BAD("--atol must be a finite number >= 0, got %g", cfg.atol);
  if (exp_init && !isnan(v0) && (!(v0 > 0) || !isfinite(v0)))
    BAD("--v0 must be a finite number > 0, got %g", v0);
  if (!isnan(ratio) && cfg.method != SB_PBE_SECTIONAL)
    fprintf(stderr, "smolbridge pbe: warning: --ratio ignored: it sets the "
                    "sectional grid (--method sectional)\n");
  if (!isnan(v0) && !exp_init)
    fprintf(stderr, "smolbridge pbe: warning: --v0 ignored: it is the mean "
                    "volume of --init exp\n");

  sb_kernel_type type;
  sb_kernel_spec spec;
  if (sb_kernel_type_from_name(kname, &type))
    BAD("--kernel %s: %s", kname, sb_last_error());
  sb_kernel_spec_init(&spec, type);
  for (int i = 0; i < nparams; i++) {
    char key[32];
    const char *eq = strchr(params[i], '=');
    if (!eq || eq == params[i] || (size_t)(eq - params[i]) >= sizeof key)
      BAD("--param needs KEY=VALUE, got '%s'", params[i]);
    memcpy(key, params[i], (size_t)(eq - params[i]));
    key[eq - params[i]] = '\0';
    for (int j = 0; j < i; j++)  /* as a key given twice in an INI file */
      if (!strncmp(params[j], params[i], (size_t)(eq - params[i]) + 1))
        BAD("--param %s given twice (%s, then %s); give each parameter "
            "once", key, params[j], params[i]);
    if (parse_num(eq + 1, &x))
      BAD("--param %s: '%s' is not a finite number", params[i], eq + 1);
    if (sb_kernel_spec_set(&spec, key, x))
      BAD("--param %s: unknown parameter '%s'; valid: K, T, mu, rho_p, "
          "rho_f, lambda, g, G, eps, nu, u2, b2 (those of --kernel %s are "
          "listed by --help)", params[i], key, kname);
    if (!listed(kernel_keys[type], key))
      fprintf(stderr, "smolbridge pbe: warning: --param %s ignored: --kernel "
              "%s has no %s (its parameters: %s)\n", params[i], kname, key,
              kernel_keys[type]);
  }
  if (sb_kernel_spec_check(&spec))
    BAD("%s", sb_last_error());
  scaled_kernel sk = {spec, n0};
  const int scale_K = type == SB_KERNEL_CONSTANT ||
                      type == SB_KERNEL_ADDITIVE ||
                      type == SB_KERNEL_MULTIPLICATIVE;
  if (scale_K)
    sk.spec.K *= n0;
  {
    /* the rate n0 K(V1, V1) of the scaled system, a normal double */
    const double rate = scale_K ? sb_kernel_spec_fn(v1, v1, &sk.spec)
                                : scaled_fn(v1, v1, &sk);
    if (!isfinite(rate) || (rate != 0.0 && fabs(rate) < DBL_MIN))
      BAD("--n0 %g: the collision rate n0 K(V1, V1) = %g per unit time is "
          "out of the range of doubles; change the units of time or "
          "volume", n0, n0 * sb_kernel_spec_fn(v1, v1, &spec));
  }
  if (cfg.atol > 0) {  /* on n: on n/n0 it is atol/n0 */
    const double a = cfg.atol / n0;
    if (!isfinite(a) || a < DBL_MIN)
      BAD("--atol %g with --n0 %g: atol/n0 is out of the range of doubles",
          cfg.atol, n0);
    cfg.atol = a;
  }

  /* times */
  size_t nt = 0, cap = 16;
  double *times = malloc(cap * sizeof *times);
  char *tcopy = malloc(strlen(times_s) + 1);
  if (!times || !tcopy)
    BAD("out of memory");
  strcpy(tcopy, times_s);
  /* every field between commas is a time (strtok would skip empty ones) */
  for (char *tok = tcopy, *next; tok; tok = next) {
    next = strchr(tok, ',');
    if (next)
      *next++ = '\0';
    if (nt == cap) {
      double *nb = realloc(times, 2 * cap * sizeof *times);
      if (!nb)
        BAD("out of memory");
      times = nb;
      cap *= 2;
    }
    if (parse_num(tok, &times[nt]) || times[nt] < 0 ||
        (nt > 0 && !(times[nt] > times[nt - 1]))) {
      fprintf(stderr, "smolbridge pbe: --times must be increasing numbers "
                      ">= 0, got '%s'\n", tok);
      free(times);
      free(tcopy);
      return 2;
    }
    nt++;
  }
  free(tcopy);
  if (nt == 0) {
    free(times);
    BAD("--times: give one or more output times");
  }

  cfg.kernel = scale_K ? sb_kernel_spec_fn : scaled_fn;
  cfg.kparams = scale_K ? (const void *)&sk.spec : (const void *)&sk;
  cfg.v1 = v1;
  if (cfg.method == SB_PBE_SECTIONAL)
    cfg.ratio = isnan(ratio) ? pow(10.0, 12.0 / (double)(cfg.nsizes - 1))
                             : ratio;
  if (isnan(v0))
    v0 = cfg.method == SB_PBE_SECTIONAL ? 1e4 * v1 : 10 * v1;

  int rc = 1;
  sb_pbe *p = sb_pbe_alloc(&cfg);
  char mpath[1100];
  out_ctx oc;
  memset(&oc, 0, sizeof oc);
  oc.quiet = quiet;
  oc.n0 = n0;
  oc.t0 = now();
  if (!p) {
    fprintf(stderr, "smolbridge pbe: %s\n", sb_last_error());
    goto done;
  }
  int st = exp_init ? sb_pbe_init_exp(p, 1.0, v0) : sb_pbe_init_mono(p, 1.0);
  if (st) {
    fprintf(stderr, "smolbridge pbe: %s\n", sb_last_error());
    goto done;
  }
  size_t len = strlen(out);
  if (len > 4 && !strcmp(out + len - 4, ".csv"))
    len -= 4;
  snprintf(mpath, sizeof mpath, "%.*s-moments.csv", (int)len, out);
  oc.dist = fopen(out, "w");
  oc.mom = fopen(mpath, "w");
  if (!oc.dist || !oc.mom) {
    fprintf(stderr, "smolbridge pbe: cannot write '%s' or '%s'\n", out,
            mpath);
    rc = 2;
    goto done;
  }
  fprintf(oc.dist, "t,k,v,n\n");
  fprintf(oc.mom, "t,M0,M1,M2,tail_n,tail_M1\n");
  {
    double m0[3];
    sb_pbe_state_moments(p, m0);
    oc.m1_0 = m0[1];
    oc.p = p;
    /* multiplicative kernel: M2 = M2(0)/(1 - K M2(0) t) for any start,
     * so gelation is at t = 1/(K M2(0)); past it the model has no
     * mass-conserving solution (post-gel models are not implemented) */
    if (type == SB_KERNEL_MULTIPLICATIVE && sk.spec.K > 0) {
      double tgel = 1.0 / (sk.spec.K * m0[2]);  /* (n0 K) (M2(0)/n0) */
      if (cfg.method == SB_PBE_SECTIONAL && times[nt - 1] > 0.5 * tgel)
        fprintf(stderr, "smolbridge pbe: warning: the sectional method's "
                "fixed pivots overestimate M2 near gelation (t_gel = %g): "
                "100 sections give 1.8x at 0.9 t_gel, 300 give 1.05x "
                "(docs/pbe.md); --method discrete or more --sizes\n", tgel);
      size_t keep = 0;
      while (keep < nt && times[keep] < tgel)
        keep++;
      if (keep < nt) {
        fprintf(stderr, "smolbridge pbe: gelation at t = 1/(K M2(0)) = %g: "
                "the multiplicative kernel makes an infinite cluster then "
                "and the population balance has no mass-conserving "
                "solution beyond it (post-gel models, Flory or "
                "Stockmayer, are not implemented); the outputs stop before "
                "t = %g\n", tgel, times[keep]);
        snprintf(oc.stop, sizeof oc.stop, "gelation at t = %g", tgel);
        nt = keep;
      }
    }
  }
  sb_pbe_report rep;
  memset(&rep, 0, sizeof rep);
  st = nt ? sb_pbe_solve(p, times, nt, on_output, &oc, &rep) : SB_SUCCESS;
  if (oc.stop[0] && st == SB_EINVAL)
    fprintf(stderr, "smolbridge pbe: %s\n", oc.stop);
  else if (nt == 0 && oc.stop[0])
    ;  /* every time past gelation: said above, nothing solved */
  else
    fprintf(stderr, "smolbridge pbe: %s; %ld steps, %ld RHS evaluations, "
            "M1 drift %.3g (relative)\n", st ? sb_last_error() : "solved",
            rep.nsteps, rep.nrhs, rep.m1_drift);
  if (!st && cfg.method == SB_PBE_SECTIONAL && rep.m1_drift > 1e-6)
    fprintf(stderr, "smolbridge pbe: warning: %.3g%% of the mass left the "
            "grid above the largest pivot (%g): raise --sizes or --ratio\n",
            100.0 * rep.m1_drift,
            sb_pbe_volumes(p)[sb_pbe_nbins(p) - 1]);
  rc = st || oc.stop[0] ? 1 : 0;
  /* the data reach the disk before gnuplot reads them */
  if (oc.dist && fclose(oc.dist) != 0) {
    fprintf(stderr, "smolbridge pbe: write error on %s\n", out);
    rc = 1;
  }
  oc.dist = NULL;
  if (!st && plot && !rc) {
    /* gnuplot script: one curve n(v) per output time */
    char gp[1100];
    snprintf(gp, sizeof gp, "%s.gp", plot);
    FILE *g = fopen(gp, "w");
    if (g) {
      fprintf(g, "set terminal pngcairo size 960,640\nset output ");
      sbc_gnuplot_string(g, plot);
      fprintf(g, "\nset logscale xy\nset xlabel 'v'\nset ylabel 'n'\n"
                 "set datafile separator ','\nset key outside\ntl = \"");
      for (size_t i = 0; i < nt; i++)
        fprintf(g, "%s%.10g", i ? " " : "", times[i]);
      fprintf(g, "\"\nplot for [i=1:words(tl)] ");
      sbc_gnuplot_string(g, out);
      fprintf(g, " every ::1 using "
                 "(($1 == real(word(tl,i)) && $4 > 0) ? $3 : 1/0):4 "
                 "with lines title 't = '.word(tl,i)\n");
      if (fclose(g) != 0 || sbc_gnuplot(NULL, gp) != 0)
        fprintf(stderr, "smolbridge pbe: could not render %s (gnuplot "
                        "missing?); script in %s\n", plot, gp);
    }
  }
done:
  if (oc.dist)
    fclose(oc.dist);
  if (oc.mom)
    fclose(oc.mom);
  sb_pbe_free(p);
  free(times);
  return rc;
}
