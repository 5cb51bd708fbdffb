#!/usr/bin/env python3
# scripts/legacy_profile.py — where a legacy frame's CPU time goes, per pass, from a perf
# recording of legacy_bench (docs/legacy.md "Where the frame time goes"):
#   perf record --call-graph dwarf,16384 -o perf.data \
#       build/bin/legacy_bench --technique legacy.fast-pcf --frames 8
#   perf script -i perf.data -F comm,tid,time,ip,sym,dso | scripts/legacy_profile.py 2 8
# Arguments: warm-up frames and timed frames of the first variant (only those are counted).
# Main-thread samples belong to the pass they run in: the function whose body Passes::run runs
# (a pass's lambda is named for the pass function that holds it), else the call below the
# technique's render() (a read-back); llvmpipe worker samples to the latest main-thread pass
# before them (Passes::run ends each pass in glFinish, so the workers' work stays inside it).
# The floors legacy_bench times between the frames (measure/roofline.h renderFloors) are left
# out, worker samples included. A frame ends where the main thread leaves render()'s read-backs;
# legacy_bench renders a variant's WARM warm-up frames first, then its timed frames (each after
# a round of floors, core/technique/frame_timing.h timeInterleavedSteadyState).
# cpu-clock samples at 4 kHz: 0.25 ms each.
import sys, re, collections
WARM=int(sys.argv[1]); FRAMES=int(sys.argv[2]); MS=0.25  # ms per cpu-clock sample (4 kHz)
def parse(f):
    head=None; chain=[]
    for line in f:
        line=line.rstrip('\n')
        if not line.strip():
            if head: yield head, chain
            head=None; chain=[]; continue
        if not line.startswith('\t') and not line.startswith(' '):
            m=re.match(r'\s*(\S+)\s+(\d+)\s+([\d.]+):',line)
            head=(m.group(1),int(m.group(2)),float(m.group(3))) if m else None
        else:
            m=re.match(r'\s*[0-9a-f]+\s+(.*) \((.*)\)$',line)
            if m: chain.append((m.group(1),m.group(2).split('/')[-1]))
    if head: yield head, chain
FLOORS='(floors)'
# render() ends in its read-backs (readRgb, readVisibilityFromAlpha: milliseconds each, so
# always sampled): a frame ends where the main thread leaves them.
def isReadBack(name): return re.search(r'(^|::)read[A-Z]', name) is not None
RENDER=re.compile(r'sl::legacy::\(anonymous namespace\)::render')
cur='(setup)'; frame=[1]; llvm_t=[]; all_t=[]; tab=collections.defaultdict(collections.Counter); total=0
for (comm,tid,t),chain in parse(sys.stdin):
    steady = WARM < frame[0] <= WARM+FRAMES
    if comm.startswith('llvmpipe'):
        if not steady or cur==FLOORS: continue
        total+=1
        tab[cur]['llvmpipe threads (raster+fragment JIT)']+=1; continue
    if comm!='legacy_bench' and not steady: continue
    if comm!='legacy_bench': total+=1
    if comm!='legacy_bench':
        tab[cur]['other thread: '+comm]+=1; continue
    syms=[s for s,_ in chain]
    prev=cur
    idx=[i for i,s in enumerate(syms) if RENDER.match(s)]
    run=[i for i,s in enumerate(syms) if s=='sl::Passes::run']
    if any('renderFloors' in x for x in syms):
        if isReadBack(cur): frame[0]+=1
        cur=FLOORS; continue
    if not any(x in ('main','_start') or 'SteadyState' in x for x in syms):
        pass  # unwinding stopped in JIT code: the sample stays with the current pass
    elif run and run[0]>0 and (syms[run[0]-1].startswith('std::_Function_handler<void ()')
                               or (syms[run[0]-1].startswith('sl::')
                                   and not syms[run[0]-1].startswith('sl::nowMilliseconds'))):
        p=syms[run[0]-1]
        m=re.search(r'<void \(\), (.*?)::\{lambda',p)
        if m: p=m.group(1)
        p=re.sub(r'\(.*','',p.replace('sl::legacy::','').replace('(anonymous namespace)::',''))
        cur=p
    elif run:
        pass  # Passes::run's own timing and glFinish (Mesa): the pass that is ending
    elif idx and idx[-1]>0:
        p=syms[idx[-1]-1]
        p=re.sub(r'\(.*','',p.replace('sl::legacy::','').replace('(anonymous namespace)::',''))
        cur=p
    elif idx: cur='render (itself)'
    else:
        cur='(outside render: context, warm-up bookkeeping)' if not any('SteadyState' in s for s in syms) else 'timing'
    if isReadBack(prev) and not isReadBack(cur): frame[0]+=1
    leafsym,leafdso=chain[0] if chain else ('?','?')
    if any('MeshSplitter' in s or 'tessellate' in s for s in syms): cat='tessellation (our code)'
    elif 'PassTimer' in ' '.join(syms) and leafdso!='legacy_bench': cat='main thread in Mesa (vbo/draw/vertex/setup/pixel paths)'
    elif any('sl::imaging' in s for s in syms) and leafdso=='legacy_bench': cat='imaging emulation (our code)'
    elif leafdso=='libLLVM-15.so.1': cat='llvmpipe code generation (LLVM)'
    elif leafdso.startswith('libOSMesa') or leafdso.startswith('[JIT]') or leafdso.startswith('libglapi') or leafdso.startswith('perf-'): cat='main thread in Mesa (vbo/draw/vertex/setup/pixel paths)'
    elif leafdso=='[kernel.kallsyms]': cat='kernel (page faults, futex)'
    elif leafdso.startswith('libc'): cat='libc (memcpy/memset/malloc)'
    else: cat='other main thread ('+leafdso+')'
    if not steady: continue
    total+=1
    tab[cur][cat]+=1
    if cat.startswith('llvmpipe code'): llvm_t.append(t)
    all_t.append(t)
COLS=[('llvmpipe threads','llvmpipe threads'),('Mesa, main thread','main thread in Mesa'),('tessellation','tessellation'),('imaging/','imaging emulation'),('kernel, libc, other',None)]
def col(cat):
    for name,prefix in COLS:
        if prefix and cat.startswith(prefix): return name
    return 'kernel, libc, other'
print(f'{FRAMES} steady frames after {WARM} warm-up frames; {total*MS/FRAMES:.1f} CPU-ms per frame on all threads (cpu-clock samples x {MS} ms / frames)\n')
print('| call below render() | ' + ' | '.join(n for n,_ in COLS) + ' | all |')
print('|---'*(len(COLS)+2)+'|')
rows=sorted(tab.items(), key=lambda kv:-sum(kv[1].values()))
sums=collections.Counter()
for p,c in rows:
    n=sum(c.values())
    if n*MS/FRAMES<0.2: continue
    per=collections.Counter()
    for k,v in c.items(): per[col(k)]+=v; sums[col(k)]+=v
    print(f'| {p} | ' + ' | '.join(f'{per[nm]*MS/FRAMES:.1f}' for nm,_ in COLS) + f' | {n*MS/FRAMES:.1f} |')
print('| all | ' + ' | '.join(f'{sums[nm]*MS/FRAMES:.1f}' for nm,_ in COLS) + f' | {total*MS/FRAMES:.1f} |')
