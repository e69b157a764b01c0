// A renderer's own implementation of shadow cones and mirror images (plain
// double arrays, no qverify code), written as a qverify-eval/1 document.
// With --bug it uses the paper's printed mirror matrix (9), whose translation
// is half the right one: qverify must catch it.
#include <cmath>
#include <cstdio>
#include <cstring>

using M4 = double[4][4];

static void sphere(double cx, double cy, double cz, double r, M4 A) {
  const double c[3] = {cx, cy, cz};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) A[i][j] = 0;
  for (int i = 0; i < 3; ++i) {
    A[i][i] = 1;
    A[i][3] = A[3][i] = -c[i];
  }
  A[3][3] = cx * cx + cy * cy + cz * cz - r * r;
}

static void print_matrix(FILE* f, const M4 m) {
  std::fprintf(f, "[");
  for (int i = 0; i < 4; ++i)
    std::fprintf(f, "%s[%.17g, %.17g, %.17g, %.17g]", i ? ", " : "", m[i][0], m[i][1], m[i][2], m[i][3]);
  std::fprintf(f, "]");
}

static void shadow(FILE* f, const char* light, const M4 A, const double L[4], bool last) {
  double AL[4] = {0, 0, 0, 0}, s = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) AL[i] += A[i][j] * L[j];
  for (int i = 0; i < 4; ++i) s += L[i] * AL[i];
  M4 P, R;
  const double h[4] = {0, 0, L[3], -L[2]};  // the plane the paper's frame sends to infinity
  const double hh[4] = {0, 0, 0, 1};
  const double* H = L[3] == 0 ? hh : h;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      P[i][j] = s * A[i][j] - AL[i] * AL[j];
      R[i][j] = AL[i] * H[j] + H[i] * AL[j];
    }
  std::fprintf(f, "    {\"quadric\": \"ball\", \"light\": \"%s\", \"status\": \"ok\", \"P\": ", light);
  print_matrix(f, P);
  std::fprintf(f, ", \"polar_plane\": [%.17g, %.17g, %.17g, %.17g], \"R\": ", AL[0], AL[1], AL[2], AL[3]);
  print_matrix(f, R);
  std::fprintf(f, "}%s\n", last ? "" : ",");
}

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const bool bug = argc > 2 && std::strcmp(argv[2], "--bug") == 0;
  FILE* f = std::fopen(argv[1], "w");
  if (!f) return 2;
  M4 A;
  sphere(0.5, -1, 2, 1.25, A);
  std::fprintf(f, "{\"format\": \"qverify-eval/1\", \"scene\": \"toy\", \"precision\": \"double\", \"method\": \"direct\",\n");
  std::fprintf(f, "  \"shadows\": [\n");
  const double lamp[4] = {3, 4, 8, 1}, sun[4] = {-1, -2, 4, 0};
  shadow(f, "lamp", A, lamp, false);
  shadow(f, "sun", A, sun, true);
  // mirror 2z + 1 = 0: reflection x -> x - 2 (n.x + d) n / (n.n)
  const double n[3] = {0, 0, 2}, d = 1, nn = 4;
  M4 M, B, T;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) M[i][j] = i == j;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) M[i][j] -= 2 * n[i] * n[j] / nn;
    M[i][3] = (bug ? -1 : -2) * d * n[i] / nn;
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      T[i][j] = 0;
      for (int k = 0; k < 4; ++k) T[i][j] += A[i][k] * M[k][j];
    }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      B[i][j] = 0;
      for (int k = 0; k < 4; ++k) B[i][j] += M[k][i] * T[k][j];
    }
  std::fprintf(f, "  ],\n  \"reflections\": [\n    {\"quadric\": \"ball\", \"mirror\": \"floor\", \"status\": \"ok\", \"M\": ");
  print_matrix(f, M);
  std::fprintf(f, ", \"B\": ");
  print_matrix(f, B);
  std::fprintf(f, "}\n  ],\n  \"skipped\": []\n}\n");
  std::fclose(f);
  return 0;
}
