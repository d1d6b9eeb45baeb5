/* engine_internal.h — the engine object shared by lib/engine*.c.  Not
 * installed; internal cross-file helpers use the sbi_ prefix. */
#ifndef SB_ENGINE_INTERNAL_H
#define SB_ENGINE_INTERNAL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_shear.h>

/* Species pairs tracked for per-pair kernels. */
#ifdef _OPENMP
#include <omp.h>
#endif

/* Threads of a parallel region of engine e (par.threads, or the OpenMP
 * default); 1 without OpenMP. */
static inline int sbi_engine_threads(const sb_engine_params *p)
{
#ifdef _OPENMP
  return p->threads > 0 ? p->threads : omp_get_max_threads();
#else
  (void)p;
  return 1;
#endif
}

#define SBI_NPAIRSP (SB_ENGINE_PAIR_SPECIES * (SB_ENGINE_PAIR_SPECIES + 1) / 2)
static inline size_t sbi_pair_index(size_t a, size_t b)
{
  if (a > b) {
    size_t t = a;
    a = b;
    b = t;
  }
  return a * (2 * SB_ENGINE_PAIR_SPECIES - a - 1) / 2 + b;
}

/* A detected collision waiting to be processed: the pair record the
 * detector saw (it may cover the rest of the step after an earlier
 * collision), the contact fraction s_rec of that record's interval, the
 * contact as a fraction of the whole step (the processing order), and
 * the versions of both particles' paths when it was detected (an event
 * whose particle has changed its path since is stale). */
typedef struct {
  double s;            /* contact fraction of the whole step */
  double s_rec;        /* ... of the record's interval p.dt */
  sb_engine_pair p;
  uint32_t vi, vj;
  /* Langevin detector: both particles' states at the contact, each
   * position in its own unwrapped frame of the step, and x_i - x_j */
  int hasc;
  double cx[2][3], cu[2][3], crel[3];
  double cdu;  /* x velocity of j's Lees-Edwards image relative to j */
} sbi_event;

/* The linked-cell grid of the last neighbour search (for re-detection
 * after a collision inside the step). */
/* A growing list of candidate pairs (i < j, two entries each). */
typedef struct {
  size_t *p;
  size_t n, cap;
} sbi_pairbuf;

/* A candidate of the Langevin search (engine_neigh.c, lsearch): slots
 * a < b of the cell order and the rank of b's cell offset in the order
 * cells() visits the neighbouring cells. */
typedef struct {
  size_t a, b;
  unsigned g;
} sbi_lpair;

/* A growing list of them. */
typedef struct {
  sbi_lpair *p;
  size_t n, cap;
} sbi_lpairbuf;

/* One thread's share of the stencil query (engine_lstencil.c): its
 * gather block (x, y, z, f; gcap members) and the candidates it found. */
typedef struct {
  double *g;
  size_t gcap;
  sbi_lpairbuf pr;
} sbi_lpart;

typedef struct {
  int valid;
  int nc[3];
  size_t stride[3];
  double inv[3];
  double cut;        /* cut-off the grid was built for, m */
  double reach;      /* detector reach of the search, m */
  double ext_max;    /* largest r + |disp| it covers, m */
} sbi_grid;

/* A Verlet list (Verlet 1967, Phys. Rev. 159:98; Allen & Tildesley 1987,
 * §5.3.1) for deterministic detectors: every pair whose start positions
 * xb were within r_i + r_j + reach + skin when it was built.  It holds for
 * a later step while 2 (max|disp| + |x0 - xb|) <= skin and the
 * particles, their radii, the box, r_max and the reach are those it was
 * built for (engine_neigh.c); a few particles that moved further (a
 * reinsertion) are searched one by one as floaters.  The cells of that
 * build stay valid for re-detection: their edge covers the same skin. */
typedef struct {
  int valid;
  size_t n, npairs, cappairs;
  size_t *pairs;             /* 2 cappairs: i < j, in cell order */
  double *xb, *rb;           /* 3 cap, cap: x0 and radius at the build */
  uint64_t *idb;             /* cap: particle ids at the build */
  unsigned char *isfloat;    /* cap: moved too far from xb: a floater */
  size_t *floats, nfloat;    /* cap: the floaters, in index order */
  size_t fsum;               /* floater searches since the build */
  double skin, reach, rmax, L[3];
  uint64_t builds, uses;     /* counters (tests, benchmarks): builds, */
  uint64_t floated;          /* steps through it, steps with floaters */
} sbi_verlet;

/* A set of particle or pair keys (never 0), with a count per key when
 * `val` is kept (engine_idmap.c). */
typedef struct {
  uint64_t *key;
  uint32_t *val;  /* NULL: a plain set */
  size_t cap, n;
} sbi_idmap;

/* Enter key (never 0), adding one to its count in a counted map; returns
 * the count before (a plain set: 1 if present), 0 if new, -1 out of
 * memory. */
long sbi_idmap_add(sbi_idmap *m, uint64_t key, int counted);
int sbi_idmap_has(const sbi_idmap *m, uint64_t key);
/* Enter key (never 0, absent) with count val (a plain set: val 0); as
 * sbi_idmap_add. */
long sbi_idmap_put(sbi_idmap *m, uint64_t key, uint32_t val);
/* The map to f (its size, whether counted, then each key and count in
 * table order; the numbers byte-reversed when swap = 1, common/internal.h
 * sbi_write_ord), and back into m (emptied first); counted: whether the
 * map keeps counts (on reading it must match the file's): 0, -1 on a
 * read or write error or out of memory, -2 on malformed data. */
int sbi_idmap_write(const sbi_idmap *m, FILE *f, int counted, int swap);
int sbi_idmap_read(sbi_idmap *m, FILE *f, int counted, int swap);
/* SB_EINVAL (message from func) if e is inside a step, i.e. func is
 * called from a callback, where it would change the step under way:
 * only the sb_engine_outcome_* functions may act there. */
#define SBI_NOT_IN_STEP(e, func)                                            \
  do {                                                                      \
    if ((e)->in_step)                                                       \
      return sbi_error(SB_EINVAL, func, "called inside a step (from a "     \
                       "callback): only the sb_engine_outcome_* functions " \
                       "may act there");                                    \
  } while (0)

/* A fingerprint of the engine's particles (FNV-1a over the count, ids
 * and positions): an observer's state saved beside a checkpoint belongs
 * to the engine with the same one (engine_checkpoint.c). */
uint64_t sbi_engine_fingerprint(const sb_engine *e);
/* SB_EINVAL (message from func about `what`) unless e is at `steps` with
 * the fingerprint `print`: the engine a state beside a checkpoint was
 * saved with. */
int sbi_engine_check_saved(const sb_engine *e, uint64_t steps,
                           uint64_t print, const char *func,
                           const char *what);
/* Free the tables (the map is then empty and usable). */
void sbi_idmap_free(sbi_idmap *m);
/* Key of the unordered pair of particle ids (never 0). */
static inline uint64_t sbi_pair_key(uint64_t a, uint64_t b)
{
  return ((a < b ? a : b) << 32 | (a < b ? b : a)) + 1;
}

struct sb_engine {
  sb_engine_params par;
  size_t n;                  /* particles in use (<= par.capacity) */
  uint64_t next_id;

  /* particles, structure of arrays ("array of 3-vectors" for x, u so that
   * the batched Langevin stepper works on them directly) */
  double *x, *u;             /* 3 cap: position (m), velocity (m/s) */
  double *x0, *u0;           /* 3 cap: state at the start of the step */
  double *disp;              /* 3 cap: displacement over the step (m) */
  double *us;                /* 3 cap: fluid velocity at x0 (m/s) */
  double *radius, *mass;     /* cap */
  size_t *species;           /* cap: index into spec[] */
  int *family;               /* cap */
  uint64_t *id;              /* cap */
  unsigned char *hit;        /* cap: collided in this step (2: removed) */

  /* paths inside the step: particle k is at sub_p + (s - sub_t) sub_v for
   * s >= sub_t (s the fraction of the step); an outcome that changes a
   * particle's end starts a new straight piece at the contact and bumps
   * its version.  The piece is stored only once an outcome changed it
   * (piece_at[k] == epoch, the step's number); before that it is the
   * whole step, x0 + s disp (engine_detect.c: piece_p, piece_v), so a step
   * without collisions writes no pieces. */
  double *sub_p, *sub_v, *sub_t; /* 3 cap, 3 cap, cap */
  uint64_t *piece_at;        /* cap */
  uint64_t epoch;            /* bumped by every detection pass */
  uint32_t *ver;             /* cap; compared within one step only */
  size_t *far;               /* cap: particles whose new piece left the
                                region of the search (engine_neigh.c) */
  size_t nfar;
  unsigned char *isfar;      /* cap */
  int redetect;              /* re-detect after an outcome (built-in
                                detectors always; custom ones on request) */
  uint64_t nredetect;        /* re-detections since the counter reset */
  struct {
    size_t k;
    double x[3];
  } declared[2];             /* positions at the collision declared by the
                                running outcome (sb_engine_outcome_path) */
  int ndeclared;
  double in_outcome_t;       /* step fraction of the running outcome */
  int in_step;               /* events of a step are being processed */

  /* species and their step coefficients */
  size_t nspec, capspec;
  sb_engine_species *spec;
  sb_langevin_coef *coef;
  double *vsd;               /* equilibrium velocity std per species */
  double rmax;               /* largest species radius */

  /* behaviour */
  sb_engine_detect_fn detect_fn;
  void *detect_ctx;
  double detect_reach;
  int detect_chord;          /* custom detector: sb_engine_set_detector_chord */
  sb_engine_outcome_fn outcome_fn;
  void *outcome_ctx;
  sb_engine_fluid fluid;
  double fluid_p[3];
  sb_engine_fluid_fn fluid_fn;
  void *fluid_ctx;

  gsl_rng *rng;

  /* time and observers */
  uint64_t steps;
  double t, t_reset;
  uint64_t ncoll, ncand, dropped;
  /* pair exposure since the reset: expo = int n(n-1)/2 dt; per species
   * pair (a <= b < SB_ENGINE_PAIR_SPECIES) pexpo = int P_ab dt with
   * P_ab = n_a n_b (a < b) or n_a (n_a - 1)/2, and the collisions pcoll */
  double expo;
  double pexpo[SBI_NPAIRSP];
  uint64_t pcoll[SBI_NPAIRSP];
  /* the collisions since the reset, for the counts' variance
   * (sb_engine_set_count_variance): each particle's with each partner
   * species, key (id << 5 | species) + 1, each pair's (sbi_pair_key), and
   * per species pair the sums of their squares (the particles of the first
   * species [0], of the second [1]; one side for a species with itself) */
  int cvar_on, cvar_lost;    /* tallying; incomplete since the reset */
  sbi_idmap cvar_part, cvar_pair;
  double cvar_sq[SBI_NPAIRSP][2], cvar_s2[SBI_NPAIRSP];
  double pairs0[SBI_NPAIRSP + 1]; /* scratch: pair counts at step start */
  uint64_t fam[SB_ENGINE_MAXFAM][SB_ENGINE_MAXFAM];
  sb_engine_sample *series;
  size_t nseries, capseries;

  /* scratch: candidate pairs, events, neighbour-search work arrays */
  size_t *pairs;             /* 2 cappairs */
  size_t npairs, cappairs;
  sbi_event *ev;
  size_t nev, capev;
  sbi_pairbuf *tb;           /* ntb: per-thread candidate lists (cells) */
  int ntb;
  double *wst;               /* 3 cap: U_s + settling (streams transport,
                                allocated on first use) */
  signed char *dhit;         /* capdet: first detection pass (parallel) */
  double *ds;                /* capdet: its contact fractions */
  size_t capdet;
  size_t *cell_of, *cell_start, *cell_list;
  size_t capcells;
  sbi_grid grid;             /* the cells of this step's search */
  double *dn;                /* cap: |disp_i| (cells, brute) */
  int dn_ready;              /* transport left dn = |disp| and its max */
  int dn_bad;                /* ... and whether one was not finite */
  double dn_max;
  double *xs;                /* 4 cap: cells: x0 and r + |disp| in cell
                                order (contiguous inner loop) */
  sbi_verlet vl;             /* cells: pairs kept over several steps */
  /* Langevin search (engine_neigh.c, lsearch): chord midpoints and
   * extents in cell order (4 lcapn), the slots in midpoint-cell order
   * (lcapn), per-slot counts (lcapn + 1), the midpoint cells' starts
   * (lcapc), the candidates of the walk and the ordered Verlet list (lpb),
   * the sort's scratch (lcap2 of them) */
  double *lxm, *lfx;
  size_t *lfl, *lcnt, *lfs;
  int *lcc;                  /* the ordered Verlet list and the Langevin
                                search: cell coordinates per slot
                                (3 lcapn) */
  double *lds;               /* the Langevin search: displacement and
                                radius per slot (4 lcapn) */
  sbi_lpairbuf lpb;
  sbi_lpair *lpr2;
  size_t lcapn, lcapc, lcap2;
  sbi_lpart *lpt;            /* the stencil query: each thread's share */
  int nlpt;
  int lstencil_off;          /* tests: 1 the Langevin search walks cell
                                by cell even where the stencil applies,
                                2 the stencil counts without AVX2 */
  size_t lsearch_stencil_n,  /* searches by the stencil, by the walk */
      lsearch_walk_n;
  size_t *order;             /* sweep: particle order along x */
  double *key;               /* sweep: sorted x */
  size_t norder;             /* particles in order[] (0: rebuild) */

  /* Langevin detector (engine_langevin.c).  Inside a step particle k
   * follows a Langevin path piece from its state (lp_x, lp_u) at step
   * fraction lp_t (position in its unwrapped frame) to its end state
   * (x, u); an outcome that changes it starts a new piece. */
  sb_langevin_hitter *lh;
  sb_engine_langevin_params lpar;
  /* the detector's counters (sb_engine_langevin_stats): each hitter is
   * reset before a call, and the call's counters are added here in a
   * fixed order (sbi_engine_langevin_fold), so that the floating-point
   * pruned_mass does not depend on the threads; allocated with lh */
  sb_langevin_hit_stats *lacc;
  /* keyed detection (streams on): slot t's hitter (slot 0: lh) and
   * Philox generator, its events of the parallel first pass; lredet
   * the pass key of the re-detections after the event being processed
   * (sbi_engine_langevin_redetect_key) */
  sb_langevin_hitter **lht;
  gsl_rng **lrt;
  struct sbi_lbuf *lbt;
  int nlt;
  double *lpm;               /* parallel first pass: each record's pruned
                              * mass, added in record order after it */
  size_t caplpm;
  uint64_t lredet;
  double lreach;             /* cached reach, m (NaN: to compute) */
  double lreach_dt;
  size_t lreach_n, lreach_nspec;
  double *lp_x, *lp_u, *lp_t;  /* 3 cap, 3 cap, cap */
  const sbi_event *contact;  /* contact of the running outcome, or NULL */
  /* an observer of the built-in detector's first contacts
   * (sbi_engine_set_observer), or NULL */
  int (*obs_skip)(const sb_engine *e, const sb_engine_pair *p, void *ctx);
  int (*obs_take)(sb_engine *e, const sb_engine_pair *p, double s,
                   void *ctx);
  void *obs_ctx;

  /* deferred removals (engine_merge.c): a particle marked hit[i] = 2 is
   * removed at the end of the step by sbi_engine_purge; nremove counts
   * the marks */
  size_t nremove;

  /* forces, Lees-Edwards, walls (engine_force.c, engine_lees.c,
   * engine_wall.c).  All zero: none of them (the historic engine). */
  double grav[3];            /* external acceleration, m/s^2 */
  int has_grav;
  sb_engine_species_fluid *sfl;  /* per species (nsfl entries; defaults
                                    beyond) */
  size_t nsfl;
  double *vset;              /* 3 per species: settling velocity (m/s) */
  size_t nvset;              /* species it was computed for (0: stale) */
  int nonlin;                /* some species has a nonlinear drag law */
  double *lam;               /* cap (nonlin): this step's rate of each
                                nonlinear-drag particle's linear step */
  size_t caplam;
  int lees;                  /* Lees-Edwards images on */
  struct sbi_shear_noise *shn;  /* per species: factor of the exact shear
                                   noise (engine_lees.c), nshn entries */
  size_t nshn;
  double le_off;             /* image shift delta in [0, L_x), m */
  int walled;                /* some direction has walls */
  sb_engine_wall wall[6];    /* face 2k (lo), 2k + 1 (hi) */
  sb_engine_walldet walldet;
  sb_engine_deposit deposit;
  uint64_t ndep[6];          /* depositions per face since the reset */
  /* open boundaries (engine_open.c): inflows, outflow counters and
   * callback; checkpoints keep the counters only */
  sb_engine_inflow inflow[SB_ENGINE_MAXINFLOW];
  uint64_t ninj[SB_ENGINE_MAXINFLOW], nskip[SB_ENGINE_MAXINFLOW];
  size_t ninflow;
  uint64_t nout[6];          /* outflows per open face since the reset */
  sb_engine_outflow_fn outflow_fn;
  void *outflow_ctx;
};

/* Smallest cell edge of the linked cells (and of sb_engine_sort, so that
 * sorted particles are scattered almost sequentially): about
 * SBI_CELL_PPC particles per cell on average.  With ~4 per cell the
 * pair loop and the per-cell bookkeeping balance in dilute systems
 * (bench_engine: 0.5 -> 4 per cell saved ~13% of a step at N = 1e5). */
#define SBI_CELL_PPC 4.0
static inline double sbi_cell_edge_min(double vol, size_t n, int dim)
{
  return pow(vol * SBI_CELL_PPC / ((double)n + 8.0), 1.0 / dim);
}

/* Verlet list: skin in units of r_max, and the fewest steps a rebuild
 * must be expected to last (displacement per step <= skin / this). */
#define SBI_VERLET_SKIN 1.0
#define SBI_VERLET_STEPS 20.0
/* Most floaters (particles searched one by one) before a rebuild; a
 * rebuild also comes once the floater searches since the last one number
 * more than the particles (a build costs about one search per particle:
 * without this a small system, n < 64, never rebuilt and ended with
 * every particle a floater). */
#define SBI_VERLET_FLOATERS(n) (64 + (n) / 4096)

/* Box helpers. */
static inline double sbi_minimg(double d, double L)
{
  if (d > 0.5 * L)
    d -= L;
  else if (d < -0.5 * L)
    d += L;
  return d;
}

/* x modulo L into [0, L), for finite x with |x| < SBI_WRAP_MAX_BOXES L
 * (sbi_wrappable; the entry points refuse the others, so the hot path
 * has no check).  x - L floor(x / L) is x itself inside the box and exact
 * for L <= x < 2 L (Sterbenz); elsewhere its rounding error is about
 * ulp(x), and the product L floor(x / L) can round past x (or x / L
 * underflow to -0 for a subnormal x < 0), leaving a result slightly
 * below 0: that is the point just below L, which rounds to L or below
 * (L is the box's 0). */
static inline double sbi_wrap(double x, double L)
{
  if (x >= L || x < 0.0) {
    x -= L * floor(x / L);
    if (x < 0.0)
      x += L;
    if (x >= L)  /* rounding of x slightly below 0 (or of L - tiny) */
      x = 0.0;
  }
  return x;
}

/* Positions farther out than SBI_WRAP_MAX_BOXES box lengths are refused
 * rather than wrapped: there ulp(x) exceeds 2^-26 L, so the wrapped
 * coordinate keeps fewer than half of a double's 53 bits (and from 2^52
 * box lengths on, where ulp(x) >= L/2, none; from DBL_MAX L on x / L
 * overflows and the wrap gave -inf).  No engine step moves a particle
 * more than half a box, so only an entry point can bring such a value. */
#define SBI_WRAP_MAX_BOXES 67108864.0 /* 2^26 */

/* 1 if x is finite and can be wrapped into a box of edge L (above), else
 * 0 (NaN too). */
static inline int sbi_wrappable(double x, double L)
{
  return fabs(x) < SBI_WRAP_MAX_BOXES * L;
}

/* Lees-Edwards image index n of a particle at height y_j seen from one at
 * y_i, dy = y_i - y_j (positions may be unwrapped by a step's flight):
 * 1 when j's nearest image is the one above the box (y_j + L_y), -1
 * below, 0 in the box (docs/engine_forces.md §3). */
static inline int sbi_lees_n(const sb_engine *e, double dy)
{
  const double Ly = e->par.L[1];
  return dy > 0.5 * Ly ? 1 : (dy < -0.5 * Ly ? -1 : 0);
}

/* The Lees-Edwards image shift delta(t) at step fraction t: delta at the
 * step's start plus G L_y t dt (not reduced modulo L_x). */
static inline double sbi_lees_delta(const sb_engine *e, double t)
{
  return e->le_off + e->fluid_p[0] * e->par.L[1] * t * e->par.dt;
}

/* The velocity particle k relaxes to over the step, component c: the
 * fluid velocity at its start (zero at rest) plus its species' settling
 * velocity (the w of the exact step, engine.c transport). */
static inline double sbi_engine_w(const sb_engine *e, size_t k, int c)
{
  const size_t sp = e->species[k];
  return (e->fluid != SB_FLUID_REST ? e->us[3 * k + c] : 0.0) +
         ((e->has_grav && sp < e->nvset) ? e->vset[3 * sp + c] : 0.0);
}

/* The neighbour-search helpers below take `who`, the public function
 * the caller entered (sb_engine_step, sb_engine_neighbours, ...), and name
 * it in their error messages. */

/* Append a candidate pair (grows the array). */
int sbi_engine_push_pair(sb_engine *e, size_t i, size_t j, const char *who);

/* Neighbour search on start positions x0 and displacements disp (NULL =
 * zero) with extra reach; fills e->pairs / e->npairs.  The three methods
 * live in engine_neigh.c (cells, brute) and engine_sweep.c (sweep). */
int sbi_engine_find_pairs(sb_engine *e, sb_engine_neigh m, const double *x0,
                          const double *disp, double reach, const char *who);
/* The Langevin search's midpoint grid (engine_neigh.c, lsearch): dim
 * axes of nf cells (strides fst, box edges L), the cells' starts fs, and in
 * cell order each member's slot fl and midpoint and extent fx (x, y, z, f;
 * 4 doubles each); a pair is wanted when
 * |m_a - m_b| <= (f_a + f_b + reach)(1 + tol) + eabs. */
typedef struct {
  int dim;
  int nf[3];
  size_t fst[3];
  double L[3];
  const size_t *fs, *fl;
  const double *fx;
  double reach, tol, eabs;
} sbi_mgrid;

/* Called with the slots a, b of a pair found; nonzero stops the search. */
typedef int (*sbi_lpair_fn)(const sb_engine *e, void *ctx, size_t a,
                            size_t b);

/* Every wanted pair of M with its first member in the cells c0..c1-1
 * once, to emit (engine_lstencil.c); blk is the caller's gather block
 * (one per thread: the cell ranges of a grid may be searched at once).
 * Only for a grid with >= 3 cells on each axis whose cell edges all
 * exceed the widest bound, (2 f_max + reach)(1 + tol) + 4 eabs.  0, or
 * -1 (out of memory, or emit's nonzero). */
int sbi_lsearch_stencil(const sb_engine *e, const sbi_mgrid *M, size_t c0,
                        size_t c1, sbi_lpart *blk, sbi_lpair_fn emit,
                        void *ctx);
int sbi_engine_sweep(sb_engine *e, const double *x0, const double *disp,
                     double reach, const char *who);
/* The search of a step (sb_engine_step): x0, disp of the engine; with the
 * cells method and a deterministic detector through the Verlet list. */
int sbi_engine_find_step_pairs(sb_engine *e, double reach);
/* Partners of particle a for re-detection after a collision inside the
 * step (engine_neigh.c): fn(e, a, k, ctx) for every k whose path can come
 * within reach of a's new path piece, which starts at step fraction t and
 * stays within ext_a of c (with Lees-Edwards: of the images of k). */
int sbi_engine_partners(sb_engine *e, size_t a, const double c[3],
                        double ext_a, double t,
                        int (*fn)(sb_engine *, size_t, size_t, void *),
                        void *ctx);
/* Largest |disp_i| (Euclidean, over the active dimensions). */
double sbi_engine_max_disp(const sb_engine *e, const double *disp);

/* Detection and processing of one step (engine_detect.c). */
int sbi_engine_detect_and_process(sb_engine *e);
/* Fill the pair record of (i, j) from x0 and disp. */
void sbi_engine_make_pair(const sb_engine *e, size_t i, size_t j,
                          sb_engine_pair *p);

/* Outcomes bookkeeping (engine_outcome.c). */
int sbi_engine_apply_outcome(sb_engine *e, const sb_engine_pair *p,
                             double s);
/* The built-in reinsertion: the pair's particle of higher id is moved
 * (its j while the ids follow the slots), so that a run does not depend
 * on the particles' order in memory (sb_engine_sort). */
int sbi_engine_reinsert_higher_id(sb_engine *e, const sb_engine_pair *p,
                                  double s, const char *who);
/* Random non-overlapping position for particle k (excluded from the
 * check), uniform in the box; SB_EMAXITER after `tries` attempts.  Inside
 * a step, `partner` is k's collision partner (tested by itself: it may sit
 * at a contact point off its path's bound), or (size_t)-1. */
int sbi_engine_random_free_position(sb_engine *e, size_t k, size_t partner,
                                    double x[3], size_t tries,
                                    const char *who);
/* Equilibrium velocity for species sp at position x into u: the fluid
 * velocity, a thermal draw and the settling velocity per component.  A
 * component that is not finite (a draw beyond the doubles) is SB_ERANGE,
 * for a fill as for a reinsertion, with a message naming the part that
 * is not (the species' velocity spread, the settling velocity) or the
 * sum that overflowed; the fluid callback's own output is checked by
 * sbi_engine_fluid_eval (SB_EINVAL).  who_k: the particle the velocity is
 * for (SIZE_MAX: a new one), named in the callback's message.  Here and
 * in the helpers below `who` is the public function entered, named in
 * the error messages. */
int sbi_engine_equilibrium_velocity(sb_engine *e, size_t sp,
                                    const double x[3], double u[3],
                                    size_t who_k, const char *who);
/* SB_SUCCESS if each of the dim coordinates of x is finite and within
 * SBI_WRAP_MAX_BOXES box lengths (sbi_wrappable), else `status` with a
 * message from who naming particle k (SIZE_MAX: "a new particle") and
 * the coordinate.  Every entry point that stores a position checks it:
 * the state never holds one that is not finite or outside the box. */
int sbi_engine_check_position(const sb_engine *e, const double x[3],
                              size_t k, int status, const char *who);
/* Fluid velocity at n positions (built-in or callback), x[3i..] being
 * particle first + i's (first = SIZE_MAX: a new particle).  A callback
 * that fails, or returns a velocity component that is not finite (of the
 * dim components), is SB_EINVAL naming the callback, the particle, the
 * component and the position. */
int sbi_engine_fluid_eval(sb_engine *e, size_t n, const double *x,
                          double *us, size_t first, const char *who);

/* Observers (engine_observe.c). */
void sbi_engine_count_collision(sb_engine *e, size_t i, size_t j);
/* Pair counts now: out[SBI_NPAIRSP] per species pair, out[SBI_NPAIRSP]
 * all pairs n(n-1)/2. */
void sbi_engine_pair_counts(const sb_engine *e, double *out);
/* Add the exposure of a step of length dt from the pair counts at its
 * start (e->pairs0) and now (trapezoid). */
void sbi_engine_add_exposure(sb_engine *e, double dt);
int sbi_engine_sample(sb_engine *e);

/* Remove the particles marked for removal (engine_merge.c). */
int sbi_engine_purge(sb_engine *e);

/* Langevin detector (engine_langevin.c). */
int sbi_engine_langevin_init(sb_engine *e);
/* Run the detector on record p starting at step fraction t; on a contact
 * returns 1 with *s (fraction of the record) and fills ev's contact
 * states and its record (rewritten from the Langevin states); 0; or < 0
 * on error. */
/* Squared minimum over s in [0, 1] of |x + s d|: how close a relative
 * chord comes (the Langevin detector's chord test). */
static inline double sbi_chord_min2(const double x[3], const double d[3])
{
  const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double b = x[0] * d[0] + x[1] * d[1] + x[2] * d[2];
  double s = a > 0.0 ? -b / a : 0.0;
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  double m2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double c = x[k] + s * d[k];
    m2 += c * c;
  }
  return m2;
}
/* sbi_chord_min2 of the record's chord dx0 + s dd. */
double sbi_pair_chord_min2(const sb_engine_pair *p);
/* 1 if the chord test of sbi_engine_langevin_detect (beyond_reach)
 * applies to every record at the start of this step with neighbour reach
 * `reach`: a pair it rejects draws nothing (engine_langevin.c). */
int sbi_engine_langevin_chord_gate(const sb_engine *e, double reach);
int sbi_engine_langevin_detect(const sb_engine *e, const sb_engine_pair *p,
                               double t, const gsl_rng *r, double *s,
                               sbi_event *ev);
/* Where sbi_engine_langevin_events hands each event (s: the fraction of
 * the record's interval); status. */
typedef int (*sbi_lsink)(void *ctx, double s, sbi_event *ev);
/* The events of record p from step fraction t with hitter lh and
 * generator r: its first contact, or with SB_OUTCOME_COUNT and no
 * observer every entry (sb_langevin_hitter_sample_all; a pair in contact
 * at t is followed to its exit first), in time order; nothing for a
 * record the observer skips.  The sampler's counters of the record are
 * added to *acc.  Status. */
int sbi_engine_langevin_events(const sb_engine *e, sb_langevin_hitter *lh,
                               const gsl_rng *r, const sb_engine_pair *p,
                               double t, sbi_lsink sink, void *ctx,
                               sb_langevin_hit_stats *acc);
/* Add the counters of one (or several) sampler calls, one, to acc: the
 * counts are summed, depth_max is the larger one, and pruned_mass is
 * added only if with_mass (the parallel pass adds it in record order
 * afterwards). */
void sbi_engine_langevin_fold(sb_langevin_hit_stats *acc,
                              const sb_langevin_hit_stats *one,
                              int with_mass);
/* Before a sampler call on lh outside sbi_engine_langevin_events (the
 * walls): reset lh; after it, sbi_engine_langevin_done adds the call's
 * counters to the engine's. */
void sbi_engine_langevin_done(const sb_engine *e, sb_langevin_hitter *lh);
/* The built-in Langevin detector on record p from step fraction t: its
 * first contact (every entry with SB_OUTCOME_COUNT) pushed as events.
 * With streams on, each record draws from its own stream, keyed by the
 * step, both particles' ids and the pass (0: the step's first pass,
 * inside the step e->lredet, set for each event by
 * sbi_engine_langevin_redetect_key), so that the results depend neither
 * on the order of the records, nor on the threads, nor on the particles'
 * order in memory; else from the engine's generator in record order.
 * Status. */
int sbi_engine_langevin_record(sb_engine *e, const sb_engine_pair *p,
                               double t);
/* The pass key of the re-detections after event ev: a hash of its time
 * and its two ids (odd, so never the first pass's 0). */
void sbi_engine_langevin_redetect_key(sb_engine *e, const sbi_event *ev);
/* The step's first pass over its np candidate records on nt > 1 threads
 * (streams on): each record's events computed in parallel, then pushed
 * in record order, as sbi_engine_langevin_record would.  Status. */
int sbi_engine_langevin_first_pass(sb_engine *e, int nt);
/* Free the per-thread slots of the keyed detection (engine_lkeyed.c). */
void sbi_engine_langevin_slots_free(sb_engine *e);
/* A new hitter with the engine's Langevin parameters (NULL: no memory). */
sb_langevin_hitter *sbi_engine_langevin_hitter(const sb_engine *e);
/* Reset every hitter's counters. */
void sbi_engine_langevin_reset_stats(sb_engine *e);
/* Push the event ev of record p (start fraction t) at fraction s of the
 * record (engine_detect.c); status. */
/* An observer of the built-in detector (the first-contact observer,
 * engine_firsthit.c), or none (NULL, NULL).  skip(e, p, ctx), nonzero to
 * leave record p alone before anything is drawn, may be called on
 * several threads at once during the step's first pass and must only
 * read.  take(e, p, s, ctx) gets the first contact of each other record
 * that has one, serially and in record order (`langevin`: with the
 * contact state readable through sb_engine_contact_state); s is the
 * fraction of the record's interval, as a custom detector's (the time
 * p->t0 + s p->dt); no event is pushed (the particles pass through, and
 * a pair overlapping at the step's start is examined as a custom
 * detector would be); it returns a status.  sb_engine_set_detect and
 * sb_engine_set_detector remove it. */
void sbi_engine_set_observer(
    sb_engine *e,
    int (*skip)(const sb_engine *e, const sb_engine_pair *p, void *ctx),
    int (*take)(sb_engine *e, const sb_engine_pair *p, double s, void *ctx),
    void *ctx);
/* The detector's contact of record p (from step fraction t) at fraction
 * s of the record's interval, with its event ev (ev->hasc: the contact
 * states): to the observer, or pushed as an event.  Status. */
int sbi_engine_deliver(sb_engine *e, const sb_engine_pair *p, double t,
                       double s, sbi_event *ev);
int sbi_engine_push_event(sb_engine *e, const sb_engine_pair *p, double t,
                          double s, sbi_event *ev);
/* Noise-free Stokes particles (B = 0, finite tau) follow curved paths,
 * which the Langevin detector follows exactly but the neighbour search's
 * chords do not cover: 1 if the step's search must widen each such
 * particle's extent by sbi_engine_det_bulge (detector langevin or
 * custom, which may call it, and such a species present). */
int sbi_engine_det_bulge_on(const sb_engine *e);
/* Bound on the distance of particle k's path over a piece of length h
 * (start velocity ua at height ya in its frame) from the piece's chord,
 * 0 for particles with noise or in free flight (engine_langevin.c). */
double sbi_engine_det_bulge(const sb_engine *e, size_t k, const double *ua,
                            double ya, double h);
/* Pieces start at the step's start. */
void sbi_engine_langevin_begin(sb_engine *e);
/* After the outcome of event ev: particle k (a partner, not removed)
 * continues from its state now (e->x, e->u, at step fraction ev->s) to
 * its end: the saved end (xe, ue) if `changed` is 0, else a fresh exact
 * Langevin step. */
int sbi_engine_langevin_continue(sb_engine *e, size_t k, const sbi_event *ev,
                                 int changed, const double xe[3],
                                 const double ue[3]);

/* Recompute per-species step coefficients after a dt change; on failure
 * the status of the first species that has none (SB_ERANGE: a coefficient
 * beyond DBL_MAX), its index in *bad (may be NULL). */
int sbi_engine_update_coef(sb_engine *e, size_t *bad);
/* A step's new state with an infinite or NaN x or u (one of the dim
 * components): every particle back to its start of step and SB_ERANGE
 * naming the first such particle (`after`: the part of the step after
 * the transport that gave it, or NULL); 0 if there is none. */
int sbi_engine_step_overflow(sb_engine *e, const char *after);
/* Every particle back to its start of step (x0, u0; disp 0): the undo of
 * sbi_engine_step_overflow, also for a failure after the transport that
 * would leave a half-made step (collision tallies are kept). */
void sbi_engine_step_undo(sb_engine *e);

/* Forces, Lees-Edwards and walls (engine_force.c, engine_lees.c,
 * engine_wall.c); each is a no-op when its feature is off. */
/* Check the combination of settings and refresh the settling velocities
 * (called at the start of every step). */
int sbi_engine_physics_prepare(sb_engine *e, const char *who);
/* Settling velocity of species sp (m/s) into *vs (NULL when there is no
 * gravity), after the checks of sbi_engine_physics_prepare: its status
 * (message from who), so that a fill, an inflow or a reinsertion fails
 * rather than draw velocities without it. */
int sbi_engine_settling(sb_engine *e, size_t sp, const double **vs,
                        const char *who);
/* After the linear transport: the nonlinear-drag step of those species
 * and, with Lees-Edwards, the exact shear correction. */
int sbi_engine_after_transport(sb_engine *e);
/* The relaxation particle k follows over the current step without its
 * noise: u(t) = w + (u_a - w) e^{-t/tau}.  For a nonlinear drag law the
 * rate and terminal slip of this step's linear step (engine_force.c,
 * tau = 1/lam, w = U_s + g' tau); else the species' tau_p and
 * sbi_engine_w (the fluid and settling velocity). */
void sbi_engine_relax(const sb_engine *e, size_t k, double *tau,
                      double w[3]);
/* 1 if particle k has a nonlinear drag law. */
int sbi_engine_nonlinear(const sb_engine *e, size_t k);
/* A nonlinear-drag particle whose state an outcome changed: its step over
 * the rest h of the step from its state now (e->x, e->u), as the step's
 * own (the rate kept for sbi_engine_relax).  A new x or u that is not
 * finite undoes the step: SB_ERANGE naming the particle
 * (sbi_engine_step_overflow). */
int sbi_engine_drag_piece(sb_engine *e, size_t k, double h);
/* Cached dimensional factor per species: L[0..2] the u_x row, L[3..6]
 * the x row; on = 0 for species that keep the OU noise (free flight,
 * nonlinear drag). */
typedef struct sbi_shear_noise {
  double G, dt, tau, B;  /* key */
  int on;
  double L[7];
} sbi_shear_noise;
/* The table for this step (*tab = NULL when the images are off or
 * G = 0); SB_ENOMEM. */
int sbi_engine_shear_noise(sb_engine *e, const sbi_shear_noise **tab);
/* Exact-mean correction of the Stokes species' x components in the
 * linear shear field (Lees-Edwards on); non-zero if a corrected x or u
 * is not finite. */
int sbi_engine_shear_correct(sb_engine *e);
/* After the periodic search: drop pairs across walls and Lees-Edwards
 * boundaries, add the pairs across the sliding boundary. */
int sbi_engine_boundary_pairs(sb_engine *e, const double *x0,
                              const double *disp, double reach, double cut,
                              const char *who);
/* The image of particle j next to particle i at step fraction t
 * (positions xi, xj in the frames of x0_i, x0_j): the shift sh to add to
 * j's position -- with Lees-Edwards the image index n = +-1 across the
 * sliding boundary times (delta(t), L_y, 0), delta(t) = delta + G L_y t
 * dt, then the minimum image in the periodic directions; none across a
 * wall -- and the image's extra velocity *du = n G L_y along x.  Returns
 * n (0 without Lees-Edwards). */
int sbi_engine_image(const sb_engine *e, const double *xi, const double *xj,
                     double t, double sh[3], double *du);
/* Pair record geometry with walls / Lees-Edwards: dx0 from the positions
 * xi, xj at the record's start (step fraction t: the image shift is
 * delta(t)), and dd shifted by the image velocity over the record. */
void sbi_engine_boundary_fix_pair(const sb_engine *e, const double *xi,
                                  const double *xj, double t,
                                  sb_engine_pair *p);
/* Lees-Edwards: out = the image of point x (at step fraction t) nearest
 * to ref -- shifted by -n (delta(t), L_y) with n = sbi_lees_n(x_y -
 * ref_y), then the minimum image of every component. */
void sbi_engine_lees_near(const sb_engine *e, const double *ref,
                          const double *x, double t, double out[3]);
/* Lees-Edwards: squared distance from p to the image of q nearest to it
 * at step fraction t; *n receives the image index (sbi_lees_n). */
double sbi_engine_lees_dist2(const sb_engine *e, const double *p,
                             const double *q, double t, int *n);
/* Inside an outcome (or between steps): the x velocity of j's image next
 * to i relative to j, n G L_y (0 without Lees-Edwards); the Langevin
 * contact's, else from the positions at the contact. */
double sbi_engine_pair_du(const sb_engine *e, const sb_engine_pair *p);
/* End of the step, after the time advanced: particles of the inflows
 * (engine_open.c). */
int sbi_engine_inject(sb_engine *e);
/* An open face's particle: count it, call the outflow callback, mark it
 * for removal (engine_open.c). */
int sbi_engine_outflow(sb_engine *e, size_t i, int face);

/* End of the step: walls (deposition, reflection), then wrapping with
 * the Lees-Edwards shift. */
int sbi_engine_boundaries(sb_engine *e);
/* Particle i back into the box through its periodic faces (and the
 * Lees-Edwards boundary), as the end of a step does: for a change made
 * outside a step. */
void sbi_engine_wrap_one(sb_engine *e, size_t i);
/* Checkpoint block of these settings (format version 3), its numbers
 * byte-reversed when swap = 1 (engine_checkpoint.c). */
int sbi_engine_physics_save(const sb_engine *e, FILE *f, int swap);
int sbi_engine_physics_load(sb_engine *e, FILE *f, int swap);
/* sb_engine_checkpoint_save and _load with the file's byte order the
 * reverse of this machine's when swap = 1 (checkpoints are
 * little-endian, swap = 0 here): what a big-endian machine does, for the
 * tests (SB_EINVAL, SB_EFORMAT on loading, for a generator whose state
 * cannot be byte-reversed: engine_checkpoint.c, rng_layout). */
int sbi_engine_checkpoint_save_ord(const sb_engine *e, const char *path,
                                   int swap);
sb_engine *sbi_engine_checkpoint_load_ord(const char *path, int swap,
                                          int *status);

#endif /* SB_ENGINE_INTERNAL_H */
