% Reference outputs of MFeval 4.0 for the packaged Magic Formula examples.
%
% Run with MFeval 4.0 on the path, e.g. from the repository root
%   octave-cli --eval "addpath('/path/to/MFeval'); addpath('/path/to/coder-stub'); run('tests/tyre/data/mfeval/generate_references.m')"
% (GNU Octave, 7.3 here; an Octave script: endfunction, rows, columns; the coder.extrinsic
% stub is described in README.md).
% Writes tests/tyre/data/mfeval/MF<v>_useMode<m>_grid.csv.gz for v = 52, 61, 62 and m = 111, 121.
%
% The inputs are built here, deterministically: per file 25 operating conditions
% (loads from near FZMIN to near FZMAX; camber 0 and +3 deg at the file's inflation
% pressure and at 0.8 / 1.2 times it, -3 deg at the inflation pressure; three speeds)
% with 12 slip points each (pure side slip, pure longitudinal slip, zero slip and
% combined slip), then a block outside the file's limits (load, camber, pressure,
% slip) that MFeval saturates.  Each row holds the inputs as given and MFeval's
% outputs (columns 1-6, 13-28 and 30 of its 30; the echoed inputs and instKya,
% a finite difference along the rows, are left out).
1;  % a script with local functions (defined first, as Octave requires)

function params = read_with_crlf(src)
    % MFeval 4.0's readTIR drops the last character of every line (it expects CR LF
    % line ends); the packaged files end lines with LF, so read a CR LF copy.
    text = fileread(src);
    text = strrep(strrep(text, sprintf('\r\n'), sprintf('\n')), sprintf('\n'), sprintf('\r\n'));
    tmp = [tempname() '.tir'];
    fid = fopen(tmp, 'w');
    fwrite(fid, text);
    fclose(fid);
    params = feval('mfeval.readTIR', tmp);
    delete(tmp);
endfunction

function inputs = build_inputs(p)
    % [Fz kappa alpha gamma Vx P] per row
    fn = p.FNOMIN;
    if p.FZMIN > 0
        low = 1.05 * p.FZMIN;
    else
        low = 0.03 * fn;
    end
    loads = [low, 0.5 * fn, fn, 1.6 * fn, 0.97 * p.FZMAX];
    pi0 = p.INFLPRES;
    alphas = deg2rad([-14 -10 -6 -3 -1.5 -0.5 0.5 1 2 4 6 9 12]);
    kappas = [-0.4 -0.2 -0.1 -0.05 -0.02 -0.005 0.005 0.01 0.03 0.06 0.12 0.25 0.5];
    speeds = [1, 0.6, 1.8] * p.LONGVL;
    conds = [];   % [Fz gamma P]
    for g = deg2rad([0 3])
        for i = 1:numel(loads)
            conds = [conds; loads(i), g, pi0; loads(i), g, pi0 * (1 + 0.2 * (2 * mod(i, 2) - 1))];
        end
    end
    for i = 1:numel(loads)
        conds = [conds; loads(i), deg2rad(-3), pi0];
    end
    inputs = [];
    for c = 1:rows(conds)
        pick = @(list, k) list(mod(5 * c + 3 * k, numel(list)) + 1);
        pts = zeros(12, 2);   % [kappa alpha]
        for k = 0:3
            pts(k + 1, :) = [0, pick(alphas, k)];
            pts(k + 5, :) = [pick(kappas, k), 0];
        end
        for k = 0:2
            pts(k + 10, :) = [pick(kappas, k + 7), pick(alphas, k + 4)];
        end
        v = speeds(mod(c, 3) + 1);
        inputs = [inputs; repmat(conds(c, 1), 12, 1), pts, repmat(conds(c, 2), 12, 1), ...
                  repmat(v, 12, 1), repmat(conds(c, 3), 12, 1)];
    end
    % outside the limits: MFeval saturates (useMode 1xx)
    a_out = min(1.1 * p.ALPMAX, deg2rad(80));
    over = [1.1 * p.FZMAX, 0.1, deg2rad(4), 1.2 * p.CAMMAX, p.LONGVL, pi0;
            0.5 * fn, 1.2 * p.KPUMAX, 0, 0, p.LONGVL, 1.1 * p.PRESMAX;
            0.5 * fn, 1.2 * p.KPUMIN, deg2rad(2), 1.2 * p.CAMMIN, p.LONGVL, 0.9 * p.PRESMIN;
            fn, 0.05, a_out, 0, p.LONGVL, pi0;
            fn, -0.05, -a_out, deg2rad(2), p.LONGVL, pi0];
    if p.FZMIN > 0
        over = [over; 0.7 * p.FZMIN, 0.05, deg2rad(-5), deg2rad(2), p.LONGVL, pi0];
    end
    inputs = [inputs; over];
endfunction

function write_table(path, inlabels, labels, inputs, outputs)
    fid = fopen(path, 'w');
    fprintf(fid, '%s\n', strjoin([inlabels, labels], ','));
    fmt = [repmat('%.17g,', 1, columns(inputs)), repmat('%.12g,', 1, columns(outputs))];
    fmt = [fmt(1:end - 1), '\n'];
    fprintf(fid, fmt, [inputs, outputs]');
    fclose(fid);
    gzip(path);
    delete(path);
endfunction

outdir = fileparts(mfilename('fullpath'));
root = fullfile(outdir, '..', '..', '..', '..');
names = {'52', '61', '62'};
modes = [111, 121];
outcols = [1 2 4 5 6 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 30];
labels = {'Fx [N]','Fy [N]','Mx [N m]','My [N m]','Mz [N m]','Re [m]','rho [m]', ...
          '2a [m]','t [m]','mux [-]','muy [-]','omega [rad/s]','Rl [m]','2b [m]', ...
          'Mzr [N m]','Cx [N/m]','Cy [N/m]','Cz [N/m]','Kya [N/rad]','sigmax [m]', ...
          'sigmay [m]','Kxk [N]'};
inlabels = {'Fz [N]','kappa [-]','alpha [rad]','gamma [rad]','Vx [m/s]','P [Pa]'};
% MFeval's package functions by their full names: in Octave the function mfeval.m
% that MFeval also installs would otherwise shadow the package +mfeval.
solver = feval('mfeval.Solver');
for n = 1:numel(names)
    src = fullfile(root, 'datasets', 'mf-examples', ...
                   ['MagicFormula' names{n} '_Parameters.converted.tir']);
    params = read_with_crlf(src);
    inputs = build_inputs(params);
    for m = modes
        out = solver.fullSteadyState(params, [inputs(:, 1:4), zeros(rows(inputs), 1), inputs(:, 5:6)], m);
        write_table(fullfile(outdir, sprintf('MF%s_useMode%d_grid.csv', names{n}, m)), ...
                    inlabels, labels, inputs, out(:, outcols));
    end
end

