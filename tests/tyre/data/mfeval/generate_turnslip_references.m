% Reference outputs of MFeval 4.0 beyond steady rolling without turn slip: turn slip,
% low speed and backwards running, a supplied wheel speed omega, and no limit checks.
%
% Run with MFeval 4.0 on the path, from the repository root:
%   octave-cli --eval "addpath('/path/to/MFeval'); addpath('/path/to/coder-stub'); warning('off', 'all'); run('tests/tyre/data/mfeval/generate_turnslip_references.m')"
% (GNU Octave 7.3 here; README.md in this folder says how to get MFeval 4.0 and the stub).
%
% Writes, in this folder,
%   MF<v>_turnslip_variant.tir          the packaged example with every turn-slip
%                                       coefficient non-zero (MF 5.2: with a
%                                       [TURNSLIP_COEFFICIENTS] and a [STRUCTURAL] section
%                                       added, which the packaged file lacks);
%   MF<v>_beyond_steady.csv.gz          MFeval's 30 outputs per row, for v = 52, 61, 62.
%
% Rows come in sweeps: one call of mfeval.Solver.fullSteadyState per sweep, so that
% output 29 (instKya, a finite difference of Fy over the post-processed slip angle along
% the rows of a call) is the difference along the sweep.  Within a sweep one input
% varies (slip angle, slip ratio, turn slip phit or speed), the others are fixed at
% values drawn deterministically (golden-ratio sequences) from broad ranges.  Blocks:
%   1 turn slip    useModes 112 122 212 222, phit -2..2 1/m, loads 0.05-1.8 FNOMIN,
%                  camber +-5 deg (MF 5.2: +-8), pressures 0.8-1.25 INFLPRES, 4-35 m/s;
%   2 low speed    the speed swept -20, -6, -2, -VXLOW ... 0 ... VXLOW, 1.4 VXLOW, 2 m/s
%                  (VXLOW of the files: 1 m/s), useModes 111 121 211 221 and, with turn-
%                  slip coefficients, 112 122 212 222;
%   3 omega        the wheel speed given (MFeval's 8th input), 0.7-1.3 times free rolling,
%                  forwards and backwards, useModes 111 121 211 (and 112 212);
%   4 no limits    useModes 211 221 with inputs beyond the file's limits (loads to 1.3
%                  FZMAX and below FZMIN, slip ratio to +-1.3, camber to +-10 deg,
%                  pressure beyond PRESMIN/PRESMAX, slip angles to 40 deg).
% Turn slip is evaluated on the turn-slip variants (all three versions) and on the packaged
% MF 6.1 and 6.2 files, which carry turn-slip coefficients; the packaged MF 5.2 file has
% none (MFeval would take its reader's built-in values, those of another tyre).
%
% Columns: variant (0 packaged, 1 turn-slip variant), block, sweep, useMode, the inputs
% as given (Fz, kappa, alpha, gamma, phit, Vx, P, omega; omega 0: not given), then
% MFeval's outputs 1-30 (11 significant digits).
%
% Held-out set: with a variable heldout_seed defined before the script runs,
%   octave-cli --eval "...; heldout_seed = 38038; run('tests/tyre/data/mfeval/generate_turnslip_references.m')"
% the script writes MF<v>_heldout_variant.tir and MF<v>_heldout.csv.gz instead: the same
% blocks with fewer sweeps, every fixed input, sweep point and turn-slip coefficient drawn
% from Octave's Mersenne twister seeded with heldout_seed (coefficients 0.6-1.4 times the
% development variant's), so that no point coincides with the development set.
1;  % a script with local functions (defined first, as Octave requires)

function params = read_with_crlf(src)
    % MFeval 4.0's readTIR drops the last character of every line (it expects CR LF
    % line ends); read a CR LF copy.
    text = fileread(src);
    text = strrep(strrep(text, sprintf('\r\n'), sprintf('\n')), sprintf('\n'), sprintf('\r\n'));
    tmp = [tempname() '.tir'];
    fid = fopen(tmp, 'w');
    fwrite(fid, text);
    fclose(fid);
    params = feval('mfeval.readTIR', tmp);
    delete(tmp);
endfunction

function text = set_entry(text, name, value)
    % Replace the value of one entry "NAME = value" of a property file.
    pattern = ['(\n' name '\s*=\s*)[^\s$!]+'];
    assert(numel(regexp(text, pattern)) == 1, ['no single entry ' name]);
    text = regexprep(text, pattern, ['$1' sprintf('%.10g', value)]);
endfunction

function write_variant(src, dst, version)
    % The packaged file with every turn-slip coefficient non-zero.
    global HELDOUT
    ts = {'PDXP1', 0.45; 'PDXP2', 0.2; 'PDXP3', 2.5; 'PKYP1', 1.3; 'PDYP1', 0.5; ...
          'PDYP2', 0.15; 'PDYP3', 1.8; 'PDYP4', 0.35; 'PHYP1', 1.1; 'PHYP2', 0.18; ...
          'PHYP3', 0.06; 'PHYP4', -3.2; 'PECP1', 0.55; 'PECP2', 0.12; 'QDTP1', 11.5; ...
          'QCRP1', 0.24; 'QCRP2', 0.13; 'QBRP1', 0.14; 'QDRP1', 1.2};
    cs = [352000, 161500, 0.12, -0.07, -0.21, 0.05];  % C_x, C_y, PCFX1-2, PCFY1-2
    seeded = '';
    if ~isempty(HELDOUT)
        for i = 1:rows(ts)
            ts{i, 2} = four_digits(ts{i, 2} * span(rand(), 0.6, 1.4));
        end
        cs = four_digits(cs .* span(rand(1, 6), 0.6, 1.4));
        seeded = sprintf(', drawn with seed %d', HELDOUT);
    end
    text = fileread(src);
    text = strrep(text, sprintf('\r\n'), sprintf('\n'));
    head = sprintf(['! Derived by tests/tyre/data/mfeval/generate_turnslip_references.m from\n' ...
                    '! datasets/mf-examples/%s (Project Chrono, BSD-3-Clause, example data):\n' ...
                    '! every turn-slip coefficient set to a non-zero value%s%s.\n'], ...
                   src(max(strfind(src, '/')) + 1:end), seeded, ...
                   ifelse_text(strcmp(version, '52'), ...
                               '; [STRUCTURAL] and [TURNSLIP_COEFFICIENTS] added', ''));
    if strcmp(version, '52')
        add = sprintf(['$----------------------------------------------------------------structural\n' ...
                       '[STRUCTURAL]\n' ...
                       'LONGITUDINAL_STIFFNESS     = %.10g\n' ...
                       'LATERAL_STIFFNESS          = %.10g\n' ...
                       'PCFX1                      = %.10g\n' ...
                       'PCFX2                      = %.10g\n' ...
                       'PCFX3                      = 0\n' ...
                       'PCFY1                      = %.10g\n' ...
                       'PCFY2                      = %.10g\n' ...
                       'PCFY3                      = 0\n' ...
                       '$-----------------------------------------------------turnslip_coefficients\n' ...
                       '[TURNSLIP_COEFFICIENTS]\n'], cs);
        for i = 1:rows(ts)
            add = [add sprintf('%-27s= %.10g\n', ts{i, 1}, ts{i, 2})];
        end
        if text(end) ~= sprintf('\n')
            text = [text sprintf('\n')];
        end
        text = [text add];
    else
        text = [sprintf('\n') text];  % so that every entry follows a line end
        for i = 1:rows(ts)
            text = set_entry(text, ts{i, 1}, ts{i, 2});
        end
        text = text(2:end);
    end
    fid = fopen(dst, 'w');
    fwrite(fid, [head text]);
    fclose(fid);
endfunction

function y = four_digits(x)
    % x rounded to four significant digits (x non-zero).
    e = 10 .^ (floor(log10(abs(x))) - 3);
    y = round(x ./ e) .* e;
endfunction

function out = ifelse_text(cond, a, b)
    if cond
        out = a;
    else
        out = b;
    end
endfunction

function u = golden(i, j)
    % A deterministic low-discrepancy number in [0, 1): the i-th of sequence j (the
    % development set); for the held-out set, the next number of the seeded twister.
    global HELDOUT
    if ~isempty(HELDOUT)
        u = rand();
        return
    end
    g = [0.6180339887498949, 0.7548776662466927, 0.5698402909980532, ...
         0.8191725133961645, 0.4142135623730951, 0.7320508075688772, ...
         0.2360679774997897, 0.6457513110645906, 0.3166247903554, 0.1622776601683795];
    u = mod(0.5 + i * g(mod(j - 1, numel(g)) + 1) + 0.137 * j, 1);
endfunction

function x = span(u, lo, hi)
    x = lo + u * (hi - lo);
endfunction

function x = points(fixed, lo, hi)
    % The sweep's points: the development set's fixed list, or as many drawn (sorted) in
    % [lo, hi] for the held-out set, with the list's first and last kept where they are
    % ends the sweep must reach (lo = fixed(1), hi = fixed(end)).
    global HELDOUT
    x = fixed(:);
    if isempty(HELDOUT)
        return
    end
    x = sort(span(rand(numel(x), 1), lo, hi));
    if lo == fixed(1) && hi == fixed(end)
        x([1 end]) = [lo; hi];
    end
endfunction

function rows_ = sweep(kind, c, p)
    % Rows [Fz kappa alpha gamma phit Vx P omega] of one sweep of `kind` at condition c.
    global HELDOUT
    switch kind
        case 'alpha'
            a = deg2rad(points([-14 -8 -4 -1.5 0 1 3 6 11], -15, 12));
            n = numel(a);
            rows_ = [repmat(c.fz, n, 1), repmat(c.kappa, n, 1), a];
        case 'kappa'
            k = points([-0.45 -0.15 -0.05 -0.012 0 0.008 0.04 0.12 0.35], -0.5, 0.4);
            n = numel(k);
            rows_ = [repmat(c.fz, n, 1), k, repmat(c.alpha, n, 1)];
        case 'phit'
            ph = points([-2 -1.1 -0.4 -0.08 0 0.03 0.25 0.9 2], -2, 2);
            n = numel(ph);
            rows_ = [repmat([c.fz c.kappa c.alpha c.gamma], n, 1), ph, ...
                     repmat([c.vx c.p c.omega], n, 1)];
            return
        case 'vx'
            v = [-20 -6 -2 -1 -0.6 -0.25 0 0.1 0.45 1 1.4 2]' * p.VXLOW;
            v(1:3) = [-20 -6 -2]';  % m/s
            v(end) = 2;
            if ~isempty(HELDOUT)  % -20, -VXLOW, 0, VXLOW, 2 m/s and points between
                u = rand(7, 1);
                w = p.VXLOW;
                v = [-20; span(sort(u(1:2)), -20, -w); -w; span(sort(u(3:4)), -w, 0); 0; ...
                     span(sort(u(5:6)), 0, w); w; span(u(7), w, 2); 2];
            end
            n = numel(v);
            rows_ = [repmat([c.fz c.kappa c.alpha c.gamma c.phit], n, 1), v, ...
                     repmat(c.p, n, 1), c.omega * v];  % omega per unit speed
            return
    end
    rows_ = [rows_, repmat([c.gamma c.phit c.vx c.p c.omega], n, 1)];
endfunction

function c = condition(i, block, p, pi0, version)
    % Fixed inputs of sweep i of a block, drawn from broad ranges.
    fn = p.FNOMIN;
    s = 10 * block;
    gmax = 5;
    if strcmp(version, '52')
        gmax = 8;
    end
    c.fz = span(golden(i, s + 1), 0.05, 1.8) * fn;
    c.kappa = span(golden(i, s + 2), -0.25, 0.25);
    c.alpha = deg2rad(span(golden(i, s + 3), -10, 10));
    c.gamma = deg2rad(span(golden(i, s + 4), -gmax, gmax));
    c.phit = span(golden(i, s + 5), -2, 2);
    c.vx = span(golden(i, s + 6), 4, 35);
    c.p = pi0;
    if ~strcmp(version, '52')
        c.p = span(golden(i, s + 7), 0.8, 1.25) * pi0;
    end
    c.omega = 0;
    if block == 4  % beyond the file's limits
        c.fz = span(golden(i, s + 1), 0.2 * p.FZMIN, 1.3 * p.FZMAX);
        if mod(i, 3) == 0
            c.fz = span(golden(i, s + 8), 0.1, 0.9) * max(p.FZMIN, 0.02 * fn);
        end
        c.kappa = span(golden(i, s + 2), -1.3, 1.3);
        c.alpha = deg2rad(span(golden(i, s + 3), -40, 40));
        c.gamma = deg2rad(span(golden(i, s + 4), -10, 10));
        if ~strcmp(version, '52')
            c.p = span(golden(i, s + 7), 0.9 * p.PRESMIN, 1.1 * p.PRESMAX);
        end
    end
endfunction

function [inputs, tags] = build(p, pi0, version, variant, R0, k)
    % Every sweep of the four blocks: inputs and [block sweep useMode] per row.
    has_ts = variant == 1 || ~strcmp(version, '52');
    kinds = {'alpha', 'kappa', 'phit'};
    inputs = [];
    tags = [];
    plan = {};  % {block, modes, number of sweeps, kinds}
    global HELDOUT
    n = [12 4 4 4 4 10];  % sweeps per mode of the plan's rows
    if ~isempty(HELDOUT)
        n = [6 3 4 3 3 4];
    end
    if has_ts
        plan(end + 1, :) = {1, [112 122 212 222], n(1), kinds};
        plan(end + 1, :) = {2, [112 122 212 222], n(2), {'vx'}};
        plan(end + 1, :) = {3, [112 212], n(3), {'alpha', 'vx', 'phit', 'kappa'}};
    end
    if variant == 0
        plan(end + 1, :) = {2, [111 121 211 221], n(4), {'vx'}};
        plan(end + 1, :) = {3, [111 121 211], n(5), {'alpha', 'vx', 'kappa', 'alpha'}};
        plan(end + 1, :) = {4, [211 221], n(6), {'alpha', 'kappa'}};
    end
    for b = 1:rows(plan)
        [block, modes, nsweeps, blockkinds] = plan{b, :};
        for m = modes
            for i = 1:nsweeps
                c = condition(i + 7 * m, block, p, pi0, version);
                kind = blockkinds{mod(i - 1, numel(blockkinds)) + 1};
                if mod(m, 10) == 1
                    c.phit = 0;  % no turn slip: MFeval ignores phit
                    if strcmp(kind, 'phit')
                        kind = 'alpha';
                    end
                end
                if block == 2  % low speed: slips, camber and spin as given
                    c.vx = 0;
                end
                if block == 3  % omega: 0.7-1.3 times free rolling [rad/s per m/s]
                    c.omega = span(golden(i, 39), 0.7, 1.3) / (0.97 * R0);
                    if ~strcmp(kind, 'vx')
                        c.vx = (2 * mod(i, 2) - 1) * c.vx;  % forwards and backwards
                        c.omega = c.omega * c.vx;
                    end
                end
                r = sweep(kind, c, p);
                % short decimals, printed exactly: 0.1 N, 1e-6 (rad), 1e-5 1/m, 0.1 mm/s,
                % 1 Pa, 1e-5 rad/s
                step = [0.1 1e-6 1e-6 1e-6 1e-5 1e-4 1 1e-5];
                r = round(r ./ step) .* step;
                k = k + 1;
                inputs = [inputs; r];
                tags = [tags; repmat([block k m], rows(r), 1)];
            end
        end
    end
endfunction

global HELDOUT
HELDOUT = [];
stem = {'_turnslip_variant.tir', '_beyond_steady.csv'};
if exist('heldout_seed', 'var') && ~isempty(heldout_seed)
    HELDOUT = heldout_seed;
    rand('twister', heldout_seed);
    stem = {'_heldout_variant.tir', '_heldout.csv'};
end
outdir = fileparts(mfilename('fullpath'));
root = fullfile(outdir, '..', '..', '..', '..');
names = {'52', '61', '62'};
labels = {'Fx [N]','Fy [N]','Fz [N]','Mx [N m]','My [N m]','Mz [N m]','kappa_out [-]', ...
          'alpha_out [rad]','gamma_out [rad]','phit_out [1/m]','Vx_out [m/s]','P_out [Pa]', ...
          'Re [m]','rho [m]','2a [m]','t [m]','mux [-]','muy [-]','omega [rad/s]','Rl [m]', ...
          '2b [m]','Mzr [N m]','Cx [N/m]','Cy [N/m]','Cz [N/m]','Kya [N/rad]','sigmax [m]', ...
          'sigmay [m]','instKya [N/rad]','Kxk [N]'};
inlabels = {'variant','block','sweep','useMode','Fz [N]','kappa [-]','alpha [rad]', ...
            'gamma [rad]','phit [1/m]','Vx [m/s]','P [Pa]','omega_in [rad/s]'};
solver = feval('mfeval.Solver');
for n = 1:numel(names)
    v = names{n};
    src = fullfile(root, 'datasets', 'mf-examples', ['MagicFormula' v '_Parameters.converted.tir']);
    variant_file = fullfile(outdir, ['MF' v stem{1}]);
    write_variant(src, variant_file, v);
    table = [];
    nsweeps = 0;  % sweeps numbered through both variants
    for variant = [0 1]
        if variant == 0
            params = read_with_crlf(src);
        else
            params = read_with_crlf(variant_file);
        end
        pi0 = params.INFLPRES;
        [inputs, tags] = build(params, pi0, v, variant, params.UNLOADED_RADIUS, nsweeps);
        nsweeps = max(tags(:, 2));
        for s = unique(tags(:, 2))'
            at = tags(:, 2) == s;
            out = solver.fullSteadyState(params, inputs(at, :), tags(find(at, 1), 3));
            table = [table; repmat(variant, sum(at), 1), tags(at, :), inputs(at, :), out];
        end
    end
    path = fullfile(outdir, ['MF' v stem{2}]);
    fid = fopen(path, 'w');
    fprintf(fid, '%s\n', strjoin([inlabels, labels], ','));
    fmt = [repmat('%d,', 1, 4), repmat('%.15g,', 1, 8), repmat('%.11g,', 1, 30)];
    fmt = [fmt(1:end - 1), '\n'];
    fprintf(fid, fmt, table');
    fclose(fid);
    gzip(path);
    delete(path);
end
