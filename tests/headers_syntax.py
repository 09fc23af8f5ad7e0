#!/usr/bin/env python3
"""Every public header compiles on its own with only the flags of compile_flags.txt.

That is what an editor (clangd) sees in a fresh clone, before any build: each header under
*/include/qmotion is parsed alone (clang -fsyntax-only, warnings as errors), so a header that
leans on an include it does not make fails here. The headers are parsed on every core, each
in its own process, so one header's includes never help another's. The test first checks
itself: a header that uses std::vector without <vector> must fail.

Usage: headers_syntax.py SOURCE_DIR CLANGXX
Exit 0 pass, 1 fail.
"""
import concurrent.futures
import os
import pathlib
import subprocess
import sys
import tempfile
import time


def parse(clang, flags, source_dir, header):
    t0 = time.monotonic()
    r = subprocess.run([clang, *flags, '-Werror', '-Wno-pragma-once-outside-header',
                        '-fsyntax-only', str(header)], cwd=source_dir, capture_output=True,
                       text=True)
    return header, r.returncode, r.stderr, time.monotonic() - t0


def main():
    source_dir, clang = pathlib.Path(sys.argv[1]), sys.argv[2]
    flags = (source_dir / 'compile_flags.txt').read_text().split('\n')
    flags = [f for f in flags if f]
    headers = sorted(p.relative_to(source_dir) for p in source_dir.glob('*/include/qmotion/**/*.hpp'))
    if len(headers) < 40:
        print(f'found only {len(headers)} public headers under */include/qmotion')
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        bad = pathlib.Path(tmp) / 'leans_on_an_include.hpp'
        bad.write_text('#pragma once\ninline std::vector<int> v;\n')
        _, rc, _, _ = parse(clang, flags, source_dir, bad)
        if rc == 0:
            print('self-test: a header using std::vector without <vector> compiled')
            return 1
    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        results = list(pool.map(lambda h: parse(clang, flags, source_dir, h), headers))
    wall = time.monotonic() - t0
    failed = [(h, err) for h, rc, err, _ in results if rc]
    for h, err in failed:
        print(f'{h}:\n{err}')
    cpu = sum(r[3] for r in results)
    slowest = sorted(results, key=lambda r: -r[3])[:5]
    print(f'{len(headers)} public headers parsed in {wall:.1f} s ({cpu:.1f} s summed); slowest: '
          + ', '.join(f'{h} {s:.1f} s' for h, _, _, s in slowest))
    if failed:
        print('headers that do not compile with compile_flags.txt alone: '
              + ' '.join(str(h) for h, _ in failed))
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
