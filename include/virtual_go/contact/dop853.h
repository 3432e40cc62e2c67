// Dormand and Prince's explicit Runge-Kutta pair of order 8 with error estimators of orders 5 and
// 3 and a dense output of order 7 (DOP853: E. Hairer, S. P. Norsett, G. Wanner, "Solving
// Ordinary Differential Equations I", 2nd ed., Springer 1993, section II.10; the coefficients
// are those published with Hairer's DOP853 code). Fixed-size state, no heap work: a step costs
// 12 evaluations (the 13th, at the step's end, is the next step's first), and the dense output 3
// more, computed only for the steps that are sampled or searched for an event.
//
// Not Boost.Odeint: it offers this order only without dense output (runge_kutta_fehlberg78) or
// as extrapolation with heap-allocated tables (bulirsch_stoer_dense_out), and its dense-output
// stepper is copied whole to keep a step for later sampling. Plane contact (plane_contact.h)
// needs event location on the dense output of steps it keeps.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace virtual_go::dop853 {

template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

// The stages of one step: k[0] = f(t0, y0), k[1..11] inside the step, k[12] = f(t0 + h, y1);
// k[13..15] only once dense output was asked for.
template <int N>
using Stages = std::array<Vector<N>, 16>;

namespace coefficients {
// Nodes c_i of the stages (c[12] = 1 is the step's end; c[13..15] the dense-output stages).
inline constexpr double c[16] = {0.0,
                                 0.526001519587677318785587544488e-01,
                                 0.789002279381515978178381316732e-01,
                                 0.118350341907227396726757197510,
                                 0.281649658092772603273242802490,
                                 0.333333333333333333333333333333,
                                 0.25,
                                 0.307692307692307692307692307692,
                                 0.651282051282051282051282051282,
                                 0.6,
                                 0.857142857142857142857142857142,
                                 1.0,
                                 1.0,
                                 0.1,
                                 0.2,
                                 0.777777777777777777777777777778};
// a[i][j]: stage i from the stages j < i. Row 12 holds the weights b of the 8th-order solution.
inline constexpr double a[16][15] = {
    {},
    {5.26001519587677318785587544488e-2},
    {1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2},
    {2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2},
    {2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1,
     9.24834003261792003115737966543e-1},
    {3.7037037037037037037037037037e-2, 0.0, 0.0, 1.70828608729473871279604482173e-1,
     1.25467687566822425016691814123e-1},
    {3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2,
     -1.7578125e-2},
    {3.70920001185047927108779319836e-2, 0.0, 0.0, 1.70383925712239993810214054705e-1,
     1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2,
     8.27378916381402288758473766002e-3},
    {6.24110958716075717114429577812e-1, 0.0, 0.0, -3.36089262944694129406857109825,
     -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1,
     2.01540675504778934086186788979e1, -4.34898841810699588477366255144e1},
    {4.77662536438264365890433908527e-1, 0.0, 0.0, -2.48811461997166764192642586468,
     -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1,
     1.52792336328824235832596922938e1, -3.32882109689848629194453265587e1,
     -2.03312017085086261358222928593e-2},
    {-9.3714243008598732571704021658e-1, 0.0, 0.0, 5.18637242884406370830023853209,
     1.09143734899672957818500254654, -8.14978701074692612513997267357,
     -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1,
     2.49360555267965238987089396762, -3.0467644718982195003823669022},
    {2.27331014751653820792359768449, 0.0, 0.0, -1.05344954667372501984066689879e1,
     -2.00087205822486249909675718444, -1.79589318631187989172765950534e1,
     2.79488845294199600508499808837e1, -2.85899827713502369474065508674,
     -8.87285693353062954433549289258, 1.23605671757943030647266201528e1,
     6.43392746015763530355970484046e-1},
    {5.42937341165687622380535766363e-2, 0.0, 0.0, 0.0, 0.0, 4.45031289275240888144113950566,
     1.89151789931450038304281599044, -5.8012039600105847814672114227,
     3.1116436695781989440891606237e-1, -1.52160949662516078556178806805e-1,
     2.01365400804030348374776537501e-1, 4.47106157277725905176885569043e-2},
    {5.61675022830479523392909219681e-2, 0.0, 0.0, 0.0, 0.0, 0.0,
     2.53500210216624811088794765333e-1, -2.46239037470802489917441475441e-1,
     -1.24191423263816360469010140626e-1, 1.5329179827876569731206322685e-1,
     8.20105229563468988491666602057e-3, 7.56789766054569976138603589584e-3, -8.298e-3},
    {3.18346481635021405060768473261e-2, 0.0, 0.0, 0.0, 0.0, 2.83009096723667755288322961402e-2,
     5.35419883074385676223797384372e-2, -5.49237485713909884646569340306e-2, 0.0, 0.0,
     -1.08347328697249322858509316994e-4, 3.82571090835658412954920192323e-4,
     -3.40465008687404560802977114492e-4, 1.41312443674632500278074618366e-1},
    {-4.28896301583791923408573538692e-1, 0.0, 0.0, 0.0, 0.0, -4.69762141536116384314449447206,
     7.68342119606259904184240953878, 4.06898981839711007970213554331,
     3.56727187455281109270669543021e-1, 0.0, 0.0, 0.0, -1.39902416515901462129418009734e-3,
     2.9475147891527723389556272149, -9.15095847217987001081870187138},
};
// The 5th-order error estimator (b - b^(5)) and the 3rd-order one (b - b^(3)), over k[0..11].
inline constexpr double e5[12] = {0.1312004499419488073250102996e-1,
                                  0.0,
                                  0.0,
                                  0.0,
                                  0.0,
                                  -0.1225156446376204440720569753e1,
                                  -0.4957589496572501915214079952,
                                  0.1664377182454986536961530415e1,
                                  -0.3503288487499736816886487290,
                                  0.3341791187130174790297318841,
                                  0.8192320648511571246570742613e-1,
                                  -0.2235530786388629525884427845e-1};
inline constexpr double e3[12] = {a[12][0] - 0.244094488188976377952755905512,
                                  0.0,
                                  0.0,
                                  0.0,
                                  0.0,
                                  a[12][5],
                                  a[12][6],
                                  a[12][7],
                                  a[12][8] - 0.733846688281611857341361741547,
                                  a[12][9],
                                  a[12][10],
                                  a[12][11] - 0.220588235294117647058823529412e-1};
// The dense output's coefficients of powers 3..6 (rows), over k[0..15].
inline constexpr double d[4][16] = {
    {-0.84289382761090128651353491142e1, 0.0, 0.0, 0.0, 0.0, 0.56671495351937776962531783590,
     -0.30689499459498916912797304727e1, 0.23846676565120698287728149680e1,
     0.21170345824450282767155149946e1, -0.87139158377797299206789907490,
     0.22404374302607882758541771650e1, 0.63157877876946881815570249290,
     -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e2,
     -0.91946323924783554000451984436e1, -0.44360363875948939664310572000e1},
    {0.10427508642579134603413151009e2, 0.0, 0.0, 0.0, 0.0, 0.24228349177525818288430175319e3,
     0.16520045171727028198505394887e3, -0.37454675472269020279518312152e3,
     -0.22113666853125306036270938578e2, 0.77334326684722638389603898808e1,
     -0.30674084731089398182061213626e2, -0.93321305264302278729567221706e1,
     0.15697238121770843886131091075e2, -0.31139403219565177677282850411e2,
     -0.93529243588444783865713862664e1, 0.35816841486394083752465898540e2},
    {0.19985053242002433820987653617e2, 0.0, 0.0, 0.0, 0.0, -0.38703730874935176555105901742e3,
     -0.18917813819516756882830838328e3, 0.52780815920542364900561016686e3,
     -0.11573902539959630126141871134e2, 0.68812326946963000169666922661e1,
     -0.10006050966910838403183860980e1, 0.77771377980534432092869265740,
     -0.27782057523535084065932004339e1, -0.60196695231264120758267380846e2,
     0.84320405506677161018159903784e2, 0.11992291136182789328035130030e2},
    {-0.25693933462703749003312586129e2, 0.0, 0.0, 0.0, 0.0, -0.15418974869023643374053993627e3,
     -0.23152937917604549567536039109e3, 0.35763911791061412378285349910e3,
     0.93405324183624310003907691704e2, -0.37458323136451633156875139351e2,
     0.10409964950896230045147246184e3, 0.29840293426660503123344363579e2,
     -0.43533456590011143754432175058e2, 0.96324553959188282948394950600e2,
     -0.39177261675615439165231486172e2, -0.14972683625798562581422125276e3},
};
}  // namespace coefficients

namespace detail {
// Rows of coefficients as types, for the sums below.
template <int I>
struct StageRow {
  static constexpr double at(int j) { return coefficients::a[I][j]; }
};
struct ErrorRow5 {
  static constexpr double at(int j) { return coefficients::e5[j]; }
};
struct ErrorRow3 {
  static constexpr double at(int j) { return coefficients::e3[j]; }
};
template <int R>
struct DenseRow {
  static constexpr double at(int j) { return coefficients::d[R][j]; }
};

// sum + sum_{J in [From, To)} C::at(J) k[J] over the terms whose coefficient is not zero,
// element by element, added in the order of J (so it rounds exactly as a loop over J does); the
// coefficients are constants, so no branch or zero term is left at run time.
template <class C, int From, int... J, int N>
void add_terms_of(Vector<N>& sum, const std::array<Vector<N>, 16>& k,
                  std::integer_sequence<int, J...>) {
  for (int n = 0; n < N; ++n) {
    double s = sum[n];
    ((C::at(From + J) != 0.0 ? (s += C::at(From + J) * k[From + J][n], 0) : 0), ...);
    sum[n] = s;
  }
}
template <class C, int From, int To, int N>
void add_terms(Vector<N>& sum, const std::array<Vector<N>, 16>& k) {
  if constexpr (From < To) {
    add_terms_of<C, From>(sum, k, std::make_integer_sequence<int, To - From>());
  }
}
}  // namespace detail

// y0 + h sum_{j<I} a[I][j] k[j]: the argument of stage I.
template <int I, int N>
Vector<N> stage_argument(double h, const Vector<N>& y0, const Stages<N>& k) {
  Vector<N> sum = coefficients::a[I][0] * k[0];
  detail::add_terms<detail::StageRow<I>, 1, I, N>(sum, k);
  return y0 + h * sum;
}

namespace detail {
// Stages I..To-1 of a step, in order: k[i] = f(t0 + c_i h, stage_argument<i>).
template <int I, int To, int N, class F>
void stages(F& f, double t0, double h, const Vector<N>& y0, Stages<N>& k) {
  if constexpr (I < To) {
    f(t0 + coefficients::c[I] * h, stage_argument<I, N>(h, y0, k), k[I]);
    stages<I + 1, To, N>(f, t0, h, y0, k);
  }
}
}  // namespace detail

// One trial step of size h from (t0, y0), with k[0] = f(t0, y0) given: fills k[1..11], the 8th-
// order solution y1 and the error estimate (see error_norm). f(t, y, dydt).
template <int N, class F>
void trial_step(F& f, double t0, double h, const Vector<N>& y0, Stages<N>& k, Vector<N>& y1,
                Vector<N>& err5, Vector<N>& err3) {
  detail::stages<1, 12, N>(f, t0, h, y0, k);
  y1 = stage_argument<12, N>(h, y0, k);
  err5 = coefficients::e5[0] * k[0];
  err3 = coefficients::e3[0] * k[0];
  detail::add_terms<detail::ErrorRow5, 1, 12, N>(err5, k);
  detail::add_terms<detail::ErrorRow3, 1, 12, N>(err3, k);
}

// Hairer's combined error of a step, measured in the per-component scales (atol + rtol |y|, as
// the caller defines them) with the maximum norm: <= 1 means the step is accepted.
template <int N>
double error_norm(double h, const Vector<N>& err5, const Vector<N>& err3, const Vector<N>& scale) {
  const double e5 = (err5.array() / scale.array()).abs().maxCoeff();
  const double e3 = (err3.array() / scale.array()).abs().maxCoeff();
  if (e5 == 0.0 && e3 == 0.0) return 0.0;
  const double denominator = std::sqrt(e5 * e5 + 0.01 * e3 * e3);
  return std::abs(h) * e5 * e5 / denominator;
}

// The next step size after one of size h with error `error` (Hairer's controller: safety 0.9,
// growth at most 6, shrinking at most to a third; no growth right after a rejection).
inline double next_step_size(double h, double error, bool after_rejection) {
  const double factor =
      error == 0.0 ? 6.0 : std::clamp(0.9 * std::pow(error, -1.0 / 8.0), 1.0 / 3.0, 6.0);
  return h * (after_rejection ? std::min(1.0, factor) : factor);
}

// Row R of the dense output: h (d[R][0] k0 + sum_{j>=5} d[R][j] k[j]).
template <int R, int N>
void dense_row(double h, const Stages<N>& k, std::array<Vector<N>, 4>& dense) {
  Vector<N> sum = coefficients::d[R][0] * k[0];
  detail::add_terms<detail::DenseRow<R>, 5, 16, N>(sum, k);
  dense[R] = h * sum;
}

// The dense output of an accepted step (k[0..12] filled): the three extra stages k[13..15] and
// the coefficients of powers 3..6.
template <int N, class F>
void dense_coefficients(F& f, double t0, double h, const Vector<N>& y0, Stages<N>& k,
                        std::array<Vector<N>, 4>& dense) {
  detail::stages<13, 16, N>(f, t0, h, y0, k);
  dense_row<0, N>(h, k, dense);
  dense_row<1, N>(h, k, dense);
  dense_row<2, N>(h, k, dense);
  dense_row<3, N>(h, k, dense);
}

// The state at theta = (t - t0) / h in [0, 1] of a step with its dense coefficients:
// y0 + theta (F0 + (1 - theta) (F1 + theta (F2 + (1 - theta) (F3 + theta (F4 + (1 - theta)
// (F5 + theta F6)))))), F0 = y1 - y0, F1 = h k0 - F0, F2 = 2 F0 - h (k0 + k12), F3..F6 dense.
template <int N>
Vector<N> interpolate(double theta, double h, const Vector<N>& y0, const Vector<N>& y1,
                      const Vector<N>& k0, const Vector<N>& k12,
                      const std::array<Vector<N>, 4>& dense) {
  const double s = 1.0 - theta;
  const Vector<N> f0 = y1 - y0;
  const Vector<N> f1 = h * k0 - f0;
  const Vector<N> f2 = 2.0 * f0 - h * (k0 + k12);
  Vector<N> y = dense[3] * theta + dense[2];
  y = y * s + dense[1];
  y = y * theta + dense[0];
  y = y * s + f2;
  y = y * theta + f1;
  y = y * s + f0;
  return y0 + theta * y;
}

}  // namespace virtual_go::dop853
